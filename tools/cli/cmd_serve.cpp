// `deepnav serve`: streams IF (a scenario synthesized on the fly, or a file) over TCP and
// UDP to any number of clients, each in its own session, paced at real time or faster.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "receiver/gnss_receiver.hpp"
#include "receiver/sources/sample_source_factory.hpp"
#include "receiver/stream/stream_protocol.hpp"
#include "receiver/stream/stream_server.hpp"
#include "receiver/stream/thread_safe_logging.hpp"
#include "signals/if_file_stream.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/scenario.hpp"
#include "signals/sim/synthesized_if_stream.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/stop_signals.hpp"

namespace deepnav::cli {
namespace {

struct ServeOptions {
  std::string scenario_path, file_path, format = "ibyte", bind = "127.0.0.1", port_file;
  double fs_hz = 0.0, if_hz = 0.0, duration_s = -1.0;
  std::optional<std::uint16_t> tcp_port, udp_port;
  unsigned threads = 1;
  int sessions = 0;
  StreamServerOptions server;
  std::vector<std::uint64_t> drop_frames;
};

/// GPS time of a file's first sample from the synthesis.json `deepnav sim` writes beside it.
std::optional<GpsTime> start_time_beside(const std::filesystem::path& file) {
  const auto json_path = file.parent_path() / "synthesis.json";
  std::ifstream in(json_path);
  if (!in) return std::nullopt;
  try {
    const auto j = nlohmann::json::parse(in);
    if (j.value("if_file", "") != file.filename().string()) return std::nullopt;
    return GpsTime{j.at("start_gps_week").get<int>(), j.at("start_gps_sow").get<double>()};
  } catch (const std::exception& e) {
    spdlog::warn("{}: not used for the GPS start time: {}", json_path.string(), e.what());
    return std::nullopt;
  }
}

/// --if for a file: a receiver takes an IF strictly inside +-fs/2 (GnssReceiver), so a
/// stream beyond it is refused here, before any client is served.
void check_file_if(const ServeOptions& o) {
  if (!(std::abs(o.if_hz) < o.fs_hz / 2))
    throw UserError(
        fmt::format("--if {} Hz: not below half the sample rate (--fs {} Hz: |IF| < {} Hz), so no "
                    "receiver could take the stream",
                    o.if_hz, o.fs_hz, o.fs_hz / 2));
}

/// The payload options of the ports served, for samples of `format` (check_frame_payload).
void check_payloads(const ServeOptions& o, SampleFormat format) {
  try {
    if (o.tcp_port) check_frame_payload("--frame-bytes", o.server.tcp_payload_bytes, format, !o.server.raw);
    if (o.udp_port) check_frame_payload("--udp-frame-bytes", o.server.udp_payload_bytes, format, !o.server.raw);
  } catch (const std::invalid_argument& e) {
    throw UserError(e.what());
  }
}

/// Opens the scenario or file once to check it, and returns how each session opens its
/// own stream; `format` becomes the stream's sample format.
std::function<std::unique_ptr<IfByteStream>()> stream_opener(const ServeOptions& o, SampleFormat& format) {
  if (o.scenario_path.empty() == o.file_path.empty()) throw UserError("give either --scenario or --file");
  if (!o.scenario_path.empty()) {
    Scenario sc;
    NavData nav;
    try {
      sc = load_scenario(o.scenario_path, DEEPNAV_SOURCE_DIR);
      if (o.duration_s > 0.0) sc.duration_s = o.duration_s;
      validate_scenario(sc);
      nav = read_rinex_nav(sc.nav_file);
    } catch (const std::exception& e) {
      throw UserError(e.what());
    }
    std::shared_ptr<const IfSynthesizer> synth;
    try {
      synth = std::make_shared<const IfSynthesizer>(sc, std::move(nav));
    } catch (const std::exception& e) {
      throw UserError(e.what());
    }
    if (!stream::streamable(sc.format))
      throw UserError(
          fmt::format("{}: format {} cannot be streamed (the stream protocol carries ibyte, ishort, "
                      "gr_complex, byte and cu8; packed formats are for files)",
                      o.scenario_path, to_string(sc.format)));
    format = sc.format;
    spdlog::info("scenario '{}': {} s, {} satellites, {} jammer(s), {} at {} Hz", sc.name, sc.duration_s,
                 synth->satellites().size(), sc.jammers.size(), to_string(sc.format), sc.sample_rate_hz);
    return [synth, threads = o.threads] { return std::make_unique<SynthesizedIfStream>(synth, threads); };
  }
  IfFileStreamOptions fo;
  fo.path = o.file_path;
  try {
    fo.format = parse_sample_format(o.format);
  } catch (const std::invalid_argument& e) {
    throw UserError(std::string("--format: ") + e.what());
  }
  if (!stream::streamable(fo.format))
    throw UserError(
        fmt::format("--format {} cannot be streamed (the stream protocol carries ibyte, ishort, "
                    "gr_complex, byte and cu8; packed formats are for files)",
                    to_string(fo.format)));
  if (!(o.fs_hz > 0.0)) throw UserError("--file needs its sample rate (--fs)");
  check_file_if(o);
  format = fo.format;
  fo.sample_rate_hz = o.fs_hz;
  fo.if_hz = o.if_hz;
  fo.start_time = start_time_beside(fo.path);
  try {
    IfFileStream check(fo);  // fail now, not in each session
  } catch (const std::exception& e) {
    throw UserError(e.what());
  }
  return [fo] { return std::make_unique<IfFileStream>(fo); };
}

void serve(ServeOptions o) {
  use_thread_safe_logger();
  if (!o.tcp_port && !o.udp_port) throw UserError("give --tcp PORT and/or --udp PORT (0: any free port)");
  SampleFormat format{};
  o.server.open_stream = stream_opener(o, format);
  check_payloads(o, format);
  o.server.bind_address = o.bind;
  o.server.tcp_port = o.tcp_port;
  o.server.udp_port = o.udp_port;
  o.server.drop_frames.insert(o.drop_frames.begin(), o.drop_frames.end());
  std::unique_ptr<StreamServer> server;
  try {
    server = std::make_unique<StreamServer>(o.server);
  } catch (const std::exception& e) {
    throw UserError(e.what());
  }
  const std::string mode = o.server.raw ? "raw" : "framed";
  const std::string pace = o.server.pace > 0.0 ? fmt::format("{}x real time", o.server.pace) : "as fast as read";
  if (o.tcp_port) spdlog::info("serving on tcp://{}:{} ({}, {})", o.bind, server->tcp_port(), mode, pace);
  if (o.udp_port) spdlog::info("serving on udp://{}:{} ({}, {})", o.bind, server->udp_port(), mode, pace);
  if (!o.port_file.empty()) {
    // Written whole under a temporary name, then renamed: a script polling for it never reads half.
    const std::string tmp = o.port_file + ".partial";
    std::ofstream(tmp) << "tcp " << server->tcp_port() << "\nudp " << server->udp_port() << "\n";
    std::filesystem::rename(tmp, o.port_file);
  }
  StopOnSignals stop;
  server->run(stop.flag(), o.sessions);
  spdlog::info("{} session(s) served", server->reports().size());
}

}  // namespace

void add_serve_command(CommandParents& parents) {
  auto o = std::make_shared<ServeOptions>();
  CLI::App* cmd = parents.root.add_subcommand(
      "serve",
      "Stream IF (a scenario synthesized on the fly, or a file) over TCP/UDP to `deepnav run --input tcp://...`");
  auto* scenario =
      cmd->add_option("--scenario", o->scenario_path, "Scenario to synthesize for each client (jammers included)")
          ->check(CLI::ExistingFile);
  auto* file = cmd->add_option("--file", o->file_path, "IF file to serve instead")->check(CLI::ExistingFile);
  scenario->excludes(file);
  cmd->add_option("--format", o->format, "--file's format: " + sample_format_choices())->capture_default_str();
  cmd->add_option("--fs", o->fs_hz, "--file's sample rate (Hz)")
      ->check(finite_above(0.0, kMaxSampleRate_hz, "a sample rate in Hz"));
  cmd->add_option("--if", o->if_hz, "--file's intermediate frequency (Hz), below half the sample rate")
      ->check(finite_in(-kMaxSampleRate_hz / 2, kMaxSampleRate_hz / 2, "a frequency in Hz"))
      ->capture_default_str();
  cmd->add_option("--duration", o->duration_s, "Override the scenario's duration (s)");
  cmd->add_option("--threads", o->threads, "Synthesis threads per session (0: all cores)")->capture_default_str();
  cmd->add_option("--tcp", o->tcp_port, "TCP port to listen on (0: any free port)");
  cmd->add_option("--udp", o->udp_port, "UDP port for subscriptions (0: any free port)");
  cmd->add_option("--bind", o->bind, "Address to listen on")->capture_default_str();
  cmd->add_option("--pace", o->server.pace,
                  "Multiple of real time by the sample clock; 0: as fast as each client reads")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--raw", o->server.raw, "Bare samples, no header or frames (a plain IQ socket)");
  cmd->add_option("--frame-bytes", o->server.tcp_payload_bytes,
                  "TCP frame payload (bytes: whole samples, at least 1024)")
      ->capture_default_str();
  cmd->add_option("--udp-frame-bytes", o->server.udp_payload_bytes,
                  "UDP frame payload (bytes: whole samples, at least 1024; one datagram each)")
      ->capture_default_str();
  cmd->add_option("--drop-frames", o->drop_frames, "UDP loss injection: sequence numbers never sent")->delimiter(',');
  cmd->add_option("--drop-rate", o->server.drop_probability, "UDP loss injection: probability of dropping each frame")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--seed", o->server.drop_seed, "Seed of --drop-rate")->capture_default_str();
  cmd->add_option("--sessions", o->sessions, "Exit after this many sessions ended (0: serve until Ctrl-C)")
      ->capture_default_str();
  cmd->add_option("--port-file", o->port_file, "Write the bound ports here ('tcp N' and 'udp N' lines) once listening");
  cmd->callback([o] { serve(*o); });
}

}  // namespace deepnav::cli
