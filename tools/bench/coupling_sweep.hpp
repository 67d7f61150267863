#pragma once
// `deepnav bench coupling`: paper 003 [docs/references.md] reproduced, in a chosen error world. Each trajectory
// is synthesized with an IMU of the paper's figures and run in loose, tight and ultra-tight
// mode, over Monte Carlo runs with fixed seeds (coupling_point.hpp). The sweep runs the
// points not yet in its folder (or lists their commands), then reports per trajectory and
// mode the mean and spread over runs of each run's RMS error, the 1-sigma error at 150 s
// beside the paper's figures, and whether ultra <= tight <= loose holds.
#include <functional>
#include <string>
#include <vector>

#include "tools/bench/coupling_point.hpp"

namespace deepnav::bench {

struct CouplingSweepSettings {
  std::vector<std::string> trajectories = coupling_trajectories();
  int runs = 2;       ///< Monte Carlo runs per trajectory
  int first_run = 0;  ///< index of the first (a slice of a larger sweep)
  CouplingPointSettings point;
  double score_at_s = 150.0;                   ///< time of the 1-sigma figures
  double score_from_s = 30.0;                  ///< the RMS errors cover this time to the end
  std::string work_dir;                        ///< where the (deleted) IF files go; empty: the temporary folder
  std::string out_dir;                         ///< finished points (a rerun resumes); empty: kept nowhere
  std::string json_path, csv_path, plot_path;  ///< optional outputs (the plot needs the CSV)
  unsigned jobs = 1;                           ///< points run at once
  bool list_commands = false;                  ///< print one command per unfinished point instead
};

/// The points of the sweep, trajectory by trajectory, run by run.
std::vector<CouplingPoint> coupling_sweep_points(const CouplingSweepSettings& settings);

/// Checks the settings (InputError naming the option), then lists the unfinished points'
/// commands, or runs them (`progress` gets the fraction done after each) and prints the
/// report, with the JSON, CSV and plot asked for.
void run_coupling_sweep(CouplingSweepSettings settings, const std::function<void(double)>& progress = {});

}  // namespace deepnav::bench
