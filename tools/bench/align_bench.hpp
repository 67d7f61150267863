#pragma once
// `deepnav bench align`: paper 000's [docs/references.md] coarse-alignment error analysis (simulated tilt
// errors beside the analytic Table 1 formulas, sweeps like its Figs. 2-4), the
// stationarity check on moving data, and the fine-alignment convergence time.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/bench/bench_report.hpp"

namespace deepnav::bench {

struct AlignBenchSettings {
  int runs = 10;  ///< fine-alignment Monte Carlo runs per grade
  std::uint64_t seed = 1;
  std::string json_path;  ///< the tables as JSON; empty: none
  std::string plots_dir;  ///< PNG plots and their data; empty: none
};

struct AlignBenchResult {
  BenchReport coarse, stationarity, fine;
  nlohmann::json coarse_sweep;  ///< every simulated case of the sweep (align_sweep.json)
  nlohmann::json fine_traces;   ///< heading error over time of every fine-alignment run (align_fine.json)
};

/// The three tables; throws InputError for fewer than one run.
AlignBenchResult align_bench(const AlignBenchSettings& settings);

/// align_bench, printed, with the JSON and plots asked for.
void run_align_bench(const AlignBenchSettings& settings);

}  // namespace deepnav::bench
