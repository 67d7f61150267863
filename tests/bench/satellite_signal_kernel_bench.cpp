// Cost of the synthesizer's per-satellite inner loop: one millisecond at 4.092 Msps.
#include <benchmark/benchmark.h>

#include <vector>

#include "signals/sim/satellite_signal_kernel.hpp"

namespace {

void BM_AddSatelliteEpoch(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<float> i(n), q(n), scratch(n);
  deepnav::SignalSegment s;
  s.carrier_step_cycles = 2345.6 / n / 1000.0;
  s.code_step_chips = 1023.0 * 1.0000015 / n;
  s.code_phase_chips = 17.3;
  s.amplitude = 1.0f;
  const auto& code = deepnav::ca_code_chips(5);
  for (auto _ : state) {
    deepnav::add_satellite_segment(i.data(), q.data(), n, s, code, scratch.data());
    benchmark::DoNotOptimize(i.data());
    benchmark::DoNotOptimize(q.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.counters["ns_per_sample"] = benchmark::Counter(static_cast<double>(state.iterations() * n),
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_AddSatelliteEpoch)->Arg(4092)->Arg(16368);

}  // namespace

BENCHMARK_MAIN();
