#pragma once
// `deepnav bench leverarm`: paper 004's [docs/references.md] Table 1 (maximum roll error 10-12 s, conventional
// attitude filter vs the filter with the vertical lever-arm state) from Monte Carlo runs
// beside the paper's numbers, the 18 cm rate-table case, and the 3-D lever-arm estimate
// with its observability verdict.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/bench/bench_report.hpp"

namespace deepnav::bench {

struct LeverArmBenchSettings {
  int runs = 20;           ///< Monte Carlo runs per lever arm
  std::uint64_t seed = 1;  ///< base seed of the random generators
  std::string json_path;   ///< the tables as JSON; empty: none
  std::string plots_dir;   ///< PNG plots and their data; empty: none
};

struct LeverArmBenchResult {
  BenchReport ship, rate_table, full_arm;
  nlohmann::json traces;  ///< the first run's error traces per case (leverarm_traces.json)
};

/// The three tables; throws InputError for fewer than one run.
LeverArmBenchResult leverarm_bench(const LeverArmBenchSettings& settings);

/// leverarm_bench, printed, with the JSON and plots asked for.
void run_leverarm_bench(const LeverArmBenchSettings& settings);

}  // namespace deepnav::bench
