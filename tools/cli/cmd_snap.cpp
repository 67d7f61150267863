// `deepnav snap`: positions from snapshots of 2 to 100 ms of IF, by coarse-time navigation
// with a navigation file and an approximate time (receiver/snapshot_positioner.hpp).
//
// Exit codes: 0 at least one snapshot solved; 3 no satellite found in any snapshot; 4 the
// navigation file has no ephemeris valid at the time hint (the satellites found are
// listed first); 5 satellites found, but no snapshot solved (each entry's reason says why).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <iostream>
#include <optional>

#include "receiver/products/nmea_writer.hpp"
#include "receiver/products/track_writers.hpp"
#include "receiver/pvt/coarse_time_pvt.hpp"
#include "receiver/sources/sample_source_factory.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/text_output_file.hpp"
#include "tools/cli/cli_checks.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/snap_report.hpp"
#include "tools/cli/snapshot_hints.hpp"
#include "tools/cli/source_options.hpp"

namespace deepnav::cli {
namespace {

struct SnapOptions {
  SourceRequest source;
  std::string nav_path;
  std::string time_hint;
  std::string position_hint;
  double start_ms = 0.0;
  int length_ms = 10;
  double every_ms = 0.0;
  std::string json_path;
  std::string nmea_path;
  std::string kml_path;
};

/// Reads up to `n` samples (fewer only at the end of the source).
std::vector<Sample> read_samples(SampleSource& source, std::size_t n) {
  std::vector<Sample> samples(n);
  std::size_t got = 0;
  while (got < n) {
    const std::size_t k = source.read(std::span<Sample>(samples.data() + got, n - got));
    if (k == 0) break;
    got += k;
  }
  samples.resize(got);
  return samples;
}

std::string date_of(const GpsTime& t) {
  const CalendarTime c = calendar_from_gps_time(t);
  return fmt::format("{:04}-{:02}-{:02}", c.year, c.month, c.day);
}

int day_of_year(const GpsTime& t) {
  const CalendarTime c = calendar_from_gps_time(t);
  int day = c.day;
  for (int m = 1; m < c.month; ++m) day += days_in_month(c.year, m);
  return day;
}

/// What is missing when the navigation file has no ephemeris for the hinted time.
std::string missing_navigation(const NavData& nav, const std::string& nav_path, const GpsTime& t_hint) {
  std::string covers = "no GPS ephemeris at all";
  if (!nav.ephemerides.empty()) {
    const auto [lo, hi] =
        std::minmax_element(nav.ephemerides.begin(), nav.ephemerides.end(), [](const auto& a, const auto& b) {
          return GpsTime{a.week, a.toe_s}.seconds_since(GpsTime{b.week, b.toe_s}) < 0.0;
        });
    covers = fmt::format("ephemerides of {} to {}", date_of({lo->week, lo->toe_s}), date_of({hi->week, hi->toe_s}));
  }
  const CalendarTime c = calendar_from_gps_time(t_hint);
  return fmt::format(
      "no fix: the navigation file '{}' has no ephemeris valid at the time hint ({}; it holds {}): a snapshot "
      "fix needs the broadcast ephemerides of {}, e.g. the IGS daily file brdc{:03}0.{:02}n, given with --nav",
      nav_path, date_of(t_hint), covers, date_of(t_hint), day_of_year(t_hint), c.year % 100);
}

SnapshotPositionerConfig positioner_config(const SampleSource& source, int length_ms) {
  SnapshotPositionerConfig c;
  c.sample_rate_hz = source.sample_rate_hz();
  c.if_hz = source.intermediate_frequency_hz();
  c.snapshot_ms = length_ms;
  return c;
}

void write_text(const std::string& path, const std::string& text) {
  TextOutputFile out(path);
  out.write(text);
  out.commit();
}

/// NMEA and KML of the solved snapshots, as `run` writes its fixes.
void write_tracks(const SnapOptions& o, const std::vector<SnapEntry>& entries, const NavData& nav, int leap_seconds) {
  std::vector<PvtSolution> fixes;
  std::string nmea;
  for (const SnapEntry& e : entries) {
    if (!e.result.fix.valid) continue;
    std::map<int, Ephemeris> ephemerides;
    std::map<SatelliteId, double> cn0;
    for (const SnapshotSignal& s : e.result.signals) {
      cn0[{GnssSystem::gps, s.prn}] = s.cn0_dbhz;
      if (const Ephemeris* eph = nav.select(s.prn, e.result.fix.receive_time)) ephemerides[s.prn] = *eph;
    }
    fixes.push_back(pvt_solution_of(e.result.fix, ephemerides));
    nmea += nmea_sentences(fixes.back(), cn0, leap_seconds);
  }
  if (!o.nmea_path.empty()) write_text(o.nmea_path, nmea);
  if (!o.kml_path.empty()) write_text(o.kml_path, kml_track(fixes, "deepnav snap"));
}

/// The snapshots' start offsets (ms after the file's first sample).
std::vector<double> snapshot_starts(const SnapOptions& o, const std::optional<double>& duration_s) {
  std::vector<double> starts{o.start_ms};
  if (o.every_ms <= 0.0) return starts;
  if (!duration_s) throw UserError("--every-ms needs a file whose length is known");
  for (double t = o.start_ms + o.every_ms; t + o.length_ms <= *duration_s * 1e3 + 1e-9; t += o.every_ms)
    starts.push_back(t);
  return starts;
}

std::vector<SnapEntry> take_snapshots(const SnapOptions& o, const OpenedSource& opened, const NavData& nav,
                                      const GpsTime& t0, const std::optional<Eigen::Vector3d>& hint) {
  SampleSource& source = *opened.source;
  SnapshotPositioner positioner(positioner_config(source, o.length_ms), nav, hint);
  const double fs = source.sample_rate_hz();
  std::vector<SnapEntry> entries;
  std::int64_t position = 0;  // samples read so far
  for (const double start_ms : snapshot_starts(o, opened.duration_s)) {
    const auto first = static_cast<std::int64_t>(std::llround(start_ms * 1e-3 * fs));
    if (first > position) position += static_cast<std::int64_t>(read_samples(source, first - position).size());
    const std::vector<Sample> samples = read_samples(source, positioner.snapshot_samples());
    position += static_cast<std::int64_t>(samples.size());
    if (samples.size() < positioner.snapshot_samples()) {
      if (!entries.empty()) break;
      throw UserError(fmt::format("{}: a {} ms snapshot from {} ms needs {} samples after it, the file has {}",
                                  opened.input, o.length_ms, start_ms, positioner.snapshot_samples(), samples.size()));
    }
    if (const std::string problem = if_sample_problem(samples, source.is_real()); !problem.empty())
      throw UserError(fmt::format("{}: {}", opened.input, problem));
    SnapEntry e;
    e.t_s = static_cast<double>(first) / fs;
    e.t_hint = t0.plus_seconds(e.t_s);
    e.length_ms = o.length_ms;
    const std::clock_t began = std::clock();  // CPU time: the command runs on one thread
    e.result = positioner.solve(samples, e.t_hint);
    e.solve_cpu_ms = 1e3 * static_cast<double>(std::clock() - began) / CLOCKS_PER_SEC;
    entries.push_back(std::move(e));
  }
  return entries;
}

void run_snap(SnapOptions o) {
  NavData nav;
  try {
    nav = read_rinex_nav(o.nav_path);
  } catch (const std::exception& e) {
    throw UserError(fmt::format("--nav: {}", e.what()));
  }
  const int leap_seconds = leap_seconds_of(nav);
  const OpenedSource opened = open_sample_source(o.source);
  const std::optional<GpsTime> t_hint = first_sample_time_hint(o.time_hint, opened.settings, leap_seconds);
  if (!t_hint)
    throw UserError(
        fmt::format("{}: no time hint: give --time-hint (the time of the file's first sample within +-2 minutes), or a "
                    "--metadata file that dates the recording (<file><timestamp> or <session><toa>)",
                    opened.input));
  const GpsTime t0 = *t_hint;
  std::optional<Eigen::Vector3d> hint;
  if (!o.position_hint.empty()) hint = parse_position_hint(o.position_hint);
  std::vector<SnapEntry> entries;
  try {
    entries = take_snapshots(o, opened, nav, t0, hint);
  } catch (const std::invalid_argument& e) {
    throw UserError(e.what());
  }
  if (!o.json_path.empty()) write_text(o.json_path, snap_document(opened.input, o.nav_path, entries).dump(2) + "\n");
  write_tracks(o, entries, nav, leap_seconds);
  const bool any_signal =
      std::any_of(entries.begin(), entries.end(), [](const auto& e) { return !e.result.signals.empty(); });
  if (!any_signal)
    throw UserError(fmt::format("{}: no satellite found in {} snapshot(s): check --fs, --if, --format, "
                                "--inverted-spectrum (or the metadata file)",
                                opened.input, entries.size()),
                    3);
  if (entries.front().result.with_ephemeris.empty()) {
    fmt::print("satellites found in the snapshot at {:.3f} s:\n{}", entries.front().t_s,
               signals_table(entries.front().result));
    std::fflush(stdout);
    throw UserError(missing_navigation(nav, o.nav_path, entries.front().t_hint), 4);
  }
  fmt::print("{}", snap_table(entries));
  std::fflush(stdout);
  if (std::none_of(entries.begin(), entries.end(), [](const auto& e) { return e.result.fix.valid; }))
    throw UserError(fmt::format("no snapshot solved: {}", entries.front().result.fix.reason), 5);
}

}  // namespace

void add_snap_command(CommandParents& parents) {
  auto o = std::make_shared<SnapOptions>();
  CLI::App* cmd = parents.root.add_subcommand(
      "snap", "Positions from snapshots of 2-100 ms of IF by coarse-time navigation (navigation file and time hint)");
  add_source_options(*cmd, o->source, SourceUse::acquisition);
  cmd->add_option("--nav", o->nav_path, "RINEX navigation file with the broadcast ephemerides of the capture's day")
      ->required();
  cmd->add_option("--time-hint", o->time_hint,
                  "Approximate time of the file's first sample: 2022-01-01T00:00:03Z (UTC) or without Z (GPS); "
                  "within +-2 minutes (default: the --metadata file's date of the recording)");
  cmd->add_option("--position-hint", o->position_hint,
                  "Approximate position LAT,LON,H (deg, deg, m), within ~100 km: narrows the search");
  cmd->add_option("--start-ms", o->start_ms, "First snapshot's start after the file's first sample (ms)")
      ->check(finite_in(0.0, 1e9, "a time in ms"))
      ->capture_default_str();
  cmd->add_option("--length-ms", o->length_ms, "Snapshot length (ms)")
      ->check(CLI::Range(2, 100))
      ->capture_default_str();
  cmd->add_option("--every-ms", o->every_ms, "Take a snapshot every this many ms to the end of the file (0: one)")
      ->check(finite_in(0.0, 1e9, "a time in ms"))
      ->capture_default_str();
  cmd->add_option("--json", o->json_path, "Write the snapshots' fixes as JSON to FILE");
  cmd->add_option("--nmea", o->nmea_path, "Write the fixes as NMEA 0183 to FILE");
  cmd->add_option("--kml", o->kml_path, "Write the fixes as a KML track to FILE");
  cmd->callback([o, cmd] {
    note_given_source_options(*cmd, o->source);
    if (o->every_ms > 0.0 && o->every_ms < o->length_ms)
      throw UserError(fmt::format("--every-ms {} is shorter than --length-ms {}: snapshots would overlap", o->every_ms,
                                  o->length_ms));
    run_snap(*o);
  });
}

}  // namespace deepnav::cli
