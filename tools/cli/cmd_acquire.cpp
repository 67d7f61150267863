// `deepnav acquire`: cold-start acquisition of an IF file, printed as a table.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "receiver/acquisition/acquisition.hpp"
#include "receiver/acquisition/galileo_acquisition.hpp"
#include "receiver/acquisition/nothing_found.hpp"
#include "receiver/sources/sample_source_factory.hpp"
#include "signals/satellite_id.hpp"
#include "signals/text_output_file.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/source_options.hpp"

namespace deepnav::cli {
namespace {

struct AcquireOptions {
  SourceRequest source;
  AcquisitionConfig acq;
  std::string prn_list;
  std::string json_path;
  std::string systems_list;  ///< --systems as given; empty: GPS alone, in the GPS-only formats
  int galileo_noncoherent = GalileoAcquisitionConfig{}.noncoherent;
};

/// The systems --systems names. Without --systems, GPS alone and the GPS-only table and JSON
/// (no system column or key), as before Galileo was searched.
struct SystemChoice {
  bool given = false;
  bool gps = true;
  bool galileo = false;
};

SystemChoice parse_systems(const std::string& text) {
  SystemChoice choice;
  if (text.empty()) return choice;
  choice = {true, false, false};
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    const auto system = parse_system_name(item);
    if (!system)
      throw UserError("--systems: '" + item + "' is not a system (expected gps, galileo or both: gps,galileo)");
    (*system == GnssSystem::gps ? choice.gps : choice.galileo) = true;
  }
  if (!choice.gps && !choice.galileo)
    throw UserError("--systems: no system named (expected gps, galileo or both: gps,galileo)");
  return choice;
}

std::vector<int> parse_prns(const std::string& text) {
  std::vector<int> prns;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    try {
      std::size_t used = 0;
      const int prn = std::stoi(item, &used);
      if (used != item.size() || prn < 1 || prn > 32) throw std::invalid_argument(item);
      prns.push_back(prn);
    } catch (const std::exception&) {
      throw UserError("--prn: '" + item + "' is not a PRN in 1..32 (expected a list like 1,5,31)");
    }
  }
  return prns;
}

nlohmann::json to_json(const AcquisitionResult& r) {
  return {{"prn", r.prn},
          {"detected", r.detected},
          {"doppler_hz", r.doppler_hz},
          {"delay_samples", r.delay_samples},
          {"code_phase_chips", r.code_phase_chips},
          {"cn0_dbhz", r.cn0_dbhz},
          {"statistic", r.statistic},
          {"threshold", r.threshold},
          {"cross_correlation_suspect", r.cross_correlation_suspect}};
}

nlohmann::json to_json(const GalileoAcquisitionResult& r) {
  return {{"system", system_name(r.satellite.system)},
          {"prn", r.satellite.prn},
          {"satellite", r.satellite.to_string()},
          {"detected", r.detected},
          {"doppler_hz", r.doppler_hz},
          {"delay_samples", r.delay_samples},
          {"code_phase_chips", r.code_phase_chips},
          {"cn0_dbhz", r.cn0_dbhz},
          {"statistic", r.statistic},
          {"threshold", r.threshold},
          {"cross_correlation_suspect", r.cross_correlation_suspect},
          {"moved_off_side_lobe", r.moved_off_side_lobe}};
}

/// What a search of several systems found: GPS and Galileo results (either may be empty).
struct SystemsFound {
  std::vector<AcquisitionResult> gps;
  std::vector<GalileoAcquisitionResult> galileo;
};

/// --json must not name the file read (or its metadata file).
void refuse_replacing_inputs(const AcquireOptions& o, const OpenedSource& opened) {
  for (const std::string& input : {opened.input, o.source.metadata}) {
    std::error_code ec;
    if (!input.empty() && std::filesystem::equivalent(o.json_path, input, ec) && !ec)
      throw UserError(fmt::format("--json '{}' would replace the input '{}': choose another file", o.json_path, input));
  }
}

/// Reads one search's samples (fewer when the file ends first).
std::vector<Sample> read_search_samples(SampleSource& source, std::size_t wanted) {
  std::vector<Sample> samples(wanted);
  std::size_t got = 0;
  while (got < samples.size()) {
    const std::size_t n = source.read(std::span<Sample>(samples.data() + got, samples.size() - got));
    if (n == 0) break;
    got += n;
  }
  samples.resize(got);
  return samples;
}

void write_json_text(const AcquireOptions& o, const std::string& text) {
  if (o.json_path == "-") {
    if (!(std::cout << text << std::flush)) throw UserError("cannot write the JSON to stdout");
    return;
  }
  try {  // complete or absent (a full disk, /dev/full: an error naming the file)
    TextOutputFile file(o.json_path);
    file.write(text);
    file.commit();
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
}

void write_json(const AcquireOptions& o, const OpenedSource& opened, const std::vector<AcquisitionResult>& results,
                const std::optional<NothingFound>& nothing) {
  nlohmann::json all = nlohmann::json::array();
  for (const auto& r : results) all.push_back(to_json(r));
  nlohmann::json out{
      {"input", opened.input}, {"sample_rate_hz", o.acq.sample_rate_hz}, {"if_hz", o.acq.if_hz}, {"results", all}};
  if (nothing) out["nothing_found"] = nothing->json();
  write_json_text(o, out.dump(2) + "\n");
}

/// With --systems: every searched satellite with its "system" and "prn" (and "satellite", "G05").
void write_systems_json(const AcquireOptions& o, const OpenedSource& opened, const SystemChoice& systems,
                        const SystemsFound& found, const std::optional<NothingFound>& nothing) {
  nlohmann::json all = nlohmann::json::array();
  for (const auto& r : found.gps) {
    nlohmann::json entry = to_json(r);
    entry["system"] = system_name(GnssSystem::gps);
    entry["satellite"] = SatelliteId{GnssSystem::gps, r.prn}.to_string();
    all.push_back(std::move(entry));
  }
  for (const auto& r : found.galileo) all.push_back(to_json(r));
  nlohmann::json names = nlohmann::json::array();
  if (systems.gps) names.push_back(system_name(GnssSystem::gps));
  if (systems.galileo) names.push_back(system_name(GnssSystem::galileo));
  nlohmann::json out{{"input", opened.input},
                     {"sample_rate_hz", o.acq.sample_rate_hz},
                     {"if_hz", o.acq.if_hz},
                     {"systems", names},
                     {"results", all}};
  if (nothing) out["nothing_found"] = nothing->json();
  write_json_text(o, out.dump(2) + "\n");
}

/// With --systems: the detected satellites of each system, with a system column.
void print_systems_table(const AcquireOptions& o, const SystemsFound& found) {
  fmt::print("{:>7} {:>4} {:>11} {:>13} {:>12} {:>9} {:>10} {:>10}\n", "system", "PRN", "doppler_hz", "delay_samples",
             "delay_chips", "cn0_dbhz", "statistic", "threshold");
  const auto row = [&](GnssSystem system, int prn, double doppler, double delay, double cn0, double statistic,
                       double threshold) {
    fmt::print("{:>7} {:>4} {:>11.1f} {:>13.2f} {:>12.3f} {:>9.1f} {:>10.1f} {:>10.1f}\n", system_name(system), prn,
               doppler, delay, delay * 1.023e6 / o.acq.sample_rate_hz, cn0, statistic, threshold);
  };
  for (const auto& r : found.gps)
    if (r.detected) row(GnssSystem::gps, r.prn, r.doppler_hz, r.delay_samples, r.cn0_dbhz, r.statistic, r.threshold);
  for (const auto& r : found.galileo)
    if (r.detected)
      row(GnssSystem::galileo, r.satellite.prn, r.doppler_hz, r.delay_samples, r.cn0_dbhz, r.statistic, r.threshold);
}

void print_table(const AcquireOptions& o, const std::vector<AcquisitionResult>& results) {
  fmt::print("{:>4} {:>11} {:>13} {:>12} {:>9} {:>10} {:>10}\n", "PRN", "doppler_hz", "delay_samples", "delay_chips",
             "cn0_dbhz", "statistic", "threshold");
  for (const auto& r : results) {
    if (!r.detected) continue;
    fmt::print("{:>4} {:>11.1f} {:>13.2f} {:>12.3f} {:>9.1f} {:>10.1f} {:>10.1f}\n", r.prn, r.doppler_hz,
               r.delay_samples, r.delay_samples * 1.023e6 / o.acq.sample_rate_hz, r.cn0_dbhz, r.statistic, r.threshold);
  }
}

GalileoAcquisitionConfig galileo_config(const AcquireOptions& o) {
  GalileoAcquisitionConfig g;
  g.sample_rate_hz = o.acq.sample_rate_hz;
  g.if_hz = o.acq.if_hz;
  g.doppler_max_hz = o.acq.doppler_max_hz;
  g.pfa = o.acq.pfa;
  g.noncoherent = o.galileo_noncoherent;
  return g;
}

void run_acquire(AcquireOptions o) {
  const SystemChoice systems = parse_systems(o.systems_list);
  const OpenedSource opened = open_sample_source(o.source);
  if (!o.json_path.empty() && o.json_path != "-" && !opened.is_stream) refuse_replacing_inputs(o, opened);
  SampleSource& source = *opened.source;
  o.acq.sample_rate_hz = source.sample_rate_hz();
  o.acq.if_hz = source.intermediate_frequency_hz();
  if (!o.prn_list.empty()) o.acq.prns = parse_prns(o.prn_list);
  std::vector<Sample> samples;
  SystemsFound found;
  try {
    std::optional<Acquisition> acquisition;
    std::optional<GalileoAcquisition> galileo;
    if (systems.gps) acquisition.emplace(o.acq);
    if (systems.galileo) galileo.emplace(galileo_config(o));
    const std::int64_t gps_wanted = acquisition ? acquisition->samples_needed() : 0;
    const std::int64_t galileo_wanted = galileo ? galileo->samples_needed() : 0;
    const std::int64_t galileo_period = galileo_wanted / o.galileo_noncoherent;
    const std::int64_t wanted = std::max(gps_wanted, galileo_wanted);
    samples = read_search_samples(source, static_cast<std::size_t>(wanted));
    if (const std::string problem = if_sample_problem(samples, source.is_real()); !problem.empty())
      throw UserError(fmt::format("{}: {}", opened.input, problem));
    // The shortest block searched: GPS's coherent block, or one Galileo code period alone.
    const std::int64_t block = acquisition ? gps_wanted / o.acq.noncoherent : galileo_period;
    const double fs = o.acq.sample_rate_hz;
    if (static_cast<std::int64_t>(samples.size()) < block)
      throw UserError(
          fmt::format("{}: {}", opened.input,
                      too_short(static_cast<double>(samples.size()) / fs, static_cast<double>(block) / fs,
                                acquisition ? "one coherent block of --coherent-ms" : "one 4 ms Galileo E1 code period")
                          .message),
          kExitNothingFound);
    if (static_cast<std::int64_t>(samples.size()) < wanted)
      spdlog::warn("{}: only {} samples available, the non-coherent sum is shorter", opened.input, samples.size());
    const std::span<const Sample> all(samples);
    if (acquisition)
      found.gps =
          acquisition->search(all.first(std::min<std::size_t>(all.size(), static_cast<std::size_t>(gps_wanted))));
    if (galileo) {
      if (static_cast<std::int64_t>(samples.size()) >= galileo_period) found.galileo = galileo->search(all);
      else spdlog::warn("{}: less than one 4 ms Galileo E1 code period of samples, Galileo not searched", opened.input);
    }
  } catch (const UserError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw UserError(e.what());
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  const bool detected =
      std::any_of(found.gps.begin(), found.gps.end(), [](const auto& r) { return r.detected; }) ||
      std::any_of(found.galileo.begin(), found.galileo.end(), [](const auto& r) { return r.detected; });
  std::optional<NothingFound> nothing;
  if (!detected && systems.gps)
    nothing = diagnose_no_satellite({o.acq, samples, strongest_correlation(found.gps)}, opened.settings,
                                    static_cast<double>(samples.size()) / o.acq.sample_rate_hz);
  if (!o.json_path.empty()) {
    if (systems.given) write_systems_json(o, opened, systems, found, nothing);
    else write_json(o, opened, found.gps, nothing);
  }
  if (o.json_path != "-") {
    if (systems.given) print_systems_table(o, found);
    else print_table(o, found.gps);
  }
  if (nothing) throw UserError(fmt::format("{}: {}", opened.input, nothing->message), kExitNothingFound);
  if (!detected)
    throw UserError(fmt::format("{}: no Galileo satellite found in {:g} ms of signal", opened.input,
                                1e3 * static_cast<double>(samples.size()) / o.acq.sample_rate_hz),
                    kExitNothingFound);
}

}  // namespace

void add_acquire_command(CommandParents& parents) {
  auto o = std::make_shared<AcquireOptions>();
  CLI::App* cmd = parents.root.add_subcommand(
      "acquire", "Cold-start FFT acquisition of an IF file: detected PRNs, Doppler, code delay");
  add_source_options(*cmd, o->source, SourceUse::acquisition);
  cmd->add_option("--doppler-max", o->acq.doppler_max_hz, "Doppler search half-width (Hz)")
      ->check(finite_in(0.0, 50000.0, "a Doppler in Hz"))
      ->capture_default_str();
  cmd->add_option("--doppler-step", o->acq.doppler_step_hz, "Doppler bin (Hz); 0: 2/(3 T)")
      ->check(finite_in(0.0, 10000.0, "a Doppler step in Hz"))
      ->capture_default_str();
  cmd->add_option("--coherent-ms", o->acq.coherent_ms, "Coherent integration (1-10 ms)")
      ->check(CLI::Range(1, 10))
      ->capture_default_str();
  cmd->add_option("--noncoherent", o->acq.noncoherent, "Coherent blocks summed non-coherently")
      ->check(CLI::Range(1, kMaxNoncoherent))
      ->capture_default_str();
  cmd->add_option("--pfa", o->acq.pfa, "False-alarm probability per PRN")
      ->check(finite_above(0.0, 0.5, "a probability"))
      ->capture_default_str();
  cmd->add_option("--prn", o->prn_list, "Only these GPS PRNs, e.g. 1,5,31");
  cmd->add_option("--systems", o->systems_list,
                  "Systems searched: gps, galileo or gps,galileo (default gps); when given, the table and --json "
                  "name each satellite's system");
  cmd->add_option("--galileo-noncoherent", o->galileo_noncoherent,
                  "Galileo E1: 4 ms code periods summed non-coherently")
      ->check(CLI::Range(1, kMaxNoncoherent))
      ->capture_default_str();
  cmd->add_option("--json", o->json_path,
                  "Write every searched PRN as JSON to FILE ('-': stdout instead of the table)");
  cmd->footer(fmt::format(
      "Exit status: 0 satellites found; {} nothing found: no satellite detected (the message names the likely "
      "cause, and --json's nothing_found the evidence) or less than one coherent block of signal; 1 an error.",
      kExitNothingFound));
  cmd->callback([o, cmd] {
    note_given_source_options(*cmd, o->source);
    run_acquire(*o);
  });
}

}  // namespace deepnav::cli
