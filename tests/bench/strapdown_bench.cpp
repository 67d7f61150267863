// Strapdown mechanization throughput: IMU samples processed per second on one core
// (target: at least 2 million per second).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "ins/strapdown.hpp"

namespace {

using deepnav::ImuSample;
using deepnav::NavState;
using deepnav::StrapdownNed;

// A turning, vibrating flight at 100 Hz: the increments vary from sample to sample
// so nothing is constant-folded. Generated once, outside the timed loop.
std::vector<ImuSample> make_samples(int n) {
  std::vector<ImuSample> samples(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double t = (k + 1) * 0.01;
    auto& s = samples[static_cast<std::size_t>(k)];
    s.t_s = t;
    s.dtheta_b_rad = 0.01 * Eigen::Vector3d(0.02 * std::sin(3.0 * t), 0.01 * std::cos(2.0 * t), 0.03);
    s.dv_b_mps = 0.01 * Eigen::Vector3d(0.5 * std::sin(t), 4.0, -9.8 + 0.1 * std::cos(5.0 * t));
  }
  return samples;
}

void BM_StrapdownNedUpdate(benchmark::State& state) {
  const int n = 100000;
  const auto samples = make_samples(n);
  NavState initial;
  initial.llh = {0.6, 2.2, 1000.0};
  initial.v_ned_mps = {100.0, 50.0, 0.0};
  std::int64_t processed = 0;
  for (auto _ : state) {
    StrapdownNed ins(initial);
    for (const auto& s : samples) ins.update(s);
    benchmark::DoNotOptimize(ins.state().llh.lat_rad);
    processed += n;
  }
  state.SetItemsProcessed(processed);
  state.counters["samples_per_s"] = benchmark::Counter(static_cast<double>(processed), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StrapdownNedUpdate)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
