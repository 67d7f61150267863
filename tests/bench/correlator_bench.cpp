// The receiver's hot path: one channel's correlator bank over 1 ms at 4.092 Msps.
// Reported as ns per sample for the whole bank (E/P/L + noise, and with VE/VL added).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "receiver/correlator.hpp"

namespace {

void correlate_one_millisecond(benchmark::State& state, double very_spacing_chips) {
  const int n = static_cast<int>(state.range(0));
  std::vector<deepnav::Sample> x(static_cast<std::size_t>(n));
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> level(-3, 3);
  for (auto& s : x) s = {static_cast<std::int16_t>(level(rng)), static_cast<std::int16_t>(level(rng))};
  deepnav::CorrelatorSpan span;
  span.carrier_step_cycles = 1234.5 / 4.092e6;
  span.code_step_chips = 1.023e6 / 4.092e6 * 1.0000008;
  span.code_phase_chips = 3.7;
  span.very_spacing_chips = very_spacing_chips;
  const auto& code = deepnav::ca_code_chips(3);
  const auto& noise = deepnav::ca_code_chips(4);
  for (auto _ : state) {
    auto sums = deepnav::correlate(x.data(), n, span, code, noise);
    benchmark::DoNotOptimize(sums);
  }
  state.counters["channel_samples_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * n, benchmark::Counter::kIsRate);
  state.counters["ns_per_sample"] = benchmark::Counter(static_cast<double>(state.iterations()) * n,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_CorrelateOneMillisecond(benchmark::State& state) { correlate_one_millisecond(state, 0.0); }
void BM_CorrelateOneMillisecondWithVeryEarlyLate(benchmark::State& state) { correlate_one_millisecond(state, 1.0); }
BENCHMARK(BM_CorrelateOneMillisecond)->Arg(4092);
BENCHMARK(BM_CorrelateOneMillisecondWithVeryEarlyLate)->Arg(4092);

}  // namespace

BENCHMARK_MAIN();
