// `deepnav nav merge`: one mixed GPS + Galileo RINEX 3 navigation file from a GPS file and a
// Galileo file of another week, the Galileo data moved by whole weeks onto the GPS data's.
#include <fmt/format.h>

#include <sstream>

#include "signals/nav_merge.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/text_output_file.hpp"
#include "tools/cli/commands.hpp"

namespace deepnav::cli {
namespace {

struct NavMergeOptions {
  std::string gps_path, galileo_path, out_path;
  int galileo_week_shift = 0;
  bool all_galileo = false;
};

void run_nav_merge(const NavMergeOptions& o) {
  const NavData gps = read_rinex_nav(o.gps_path);
  const NavData galileo = read_rinex_nav(o.galileo_path);
  NavMergeRequest request;
  request.galileo_week_shift = o.galileo_week_shift;
  request.inav_only = !o.all_galileo;
  NavData merged;
  try {
    merged = merge_gps_galileo(gps, galileo, request);
  } catch (const std::invalid_argument& e) {
    throw UserError(fmt::format("--galileo-week-shift {}: {}", o.galileo_week_shift, e.what()));
  } catch (const std::runtime_error& e) {
    throw UserError(e.what());
  }
  std::ostringstream text;
  write_rinex3_nav(text, merged, "deepnav nav merge");
  TextOutputFile out(o.out_path);
  out.write(text.str());
  out.commit();
  fmt::print("wrote {}: {} GPS and {} Galileo records (Galileo moved by {} weeks)\n", o.out_path,
             merged.ephemerides.size(), merged.galileo_ephemerides.size(), o.galileo_week_shift);
}

}  // namespace

void add_nav_command(CommandParents& parents) {
  CLI::App* nav = parents.root.add_subcommand("nav", "Broadcast navigation files");
  nav->require_subcommand(1);
  auto opts = std::make_shared<NavMergeOptions>();
  CLI::App* merge = nav->add_subcommand(
      "merge",
      "Write one RINEX 3.04 mixed file from a GPS and a Galileo navigation file, moving the Galileo data by "
      "whole weeks");
  merge->add_option("--gps", opts->gps_path, "GPS navigation file (RINEX 2 or 3)")
      ->required()
      ->check(CLI::ExistingFile);
  merge->add_option("--galileo", opts->galileo_path, "Galileo navigation file (RINEX 3)")
      ->required()
      ->check(CLI::ExistingFile);
  merge->add_option("--galileo-week-shift", opts->galileo_week_shift,
                    "whole weeks added to the Galileo week numbers (toe/toc, GAGP, GAUT); seconds of week unchanged");
  merge->add_flag("--all-galileo", opts->all_galileo,
                  "keep F/NAV records too (by default only E1-B I/NAV records are kept)");
  merge->add_option("--out", opts->out_path, "file to write")->required();
  merge->callback([opts] { run_nav_merge(*opts); });
}

}  // namespace deepnav::cli
