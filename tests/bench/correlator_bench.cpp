// The receiver's hot path: one channel's correlator bank over 1 ms at 4.092 Msps, for each
// kernel the CPU can run, with E/P/L + noise and with VE/VL added; and a 12-channel block
// (every channel correlating the same 4092 samples with its own span, as the receiver
// does it), with and without the noise tap (the receiver runs it on one code period per
// integration). Reported as channel-samples per second (samples times channels).
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "receiver/tracking/correlator.hpp"

namespace {

/// 2-bit-like samples, as from a low-resolution front end.
std::vector<deepnav::Sample> samples(int n) {
  std::vector<deepnav::Sample> x(static_cast<std::size_t>(n));
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> level(-3, 3);
  for (auto& s : x) s = {static_cast<std::int16_t>(level(rng)), static_cast<std::int16_t>(level(rng))};
  return x;
}

deepnav::CorrelatorSpan span_for(int channel, double very_spacing_chips, bool noise_tap = true) {
  deepnav::CorrelatorSpan span;
  span.noise_tap = noise_tap;
  span.carrier_step_cycles = (1234.5 + 731.0 * channel) / 4.092e6;
  span.carrier_phase_cycles = 0.113 * channel;
  span.code_step_chips = 1.023e6 / 4.092e6 * (1.0000008 + 1e-7 * channel);
  span.code_phase_chips = 3.7 + 83.1 * channel;
  span.very_spacing_chips = very_spacing_chips;
  return span;
}

void set_rate(benchmark::State& state, double channel_samples_per_iteration) {
  state.counters["channel_samples_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * channel_samples_per_iteration, benchmark::Counter::kIsRate);
  state.counters["ns_per_channel_sample"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * channel_samples_per_iteration,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void one_channel(benchmark::State& state, deepnav::CorrelatorKernel kernel, double very_spacing_chips) {
  const int n = 4092;
  const auto x = samples(n);
  const deepnav::CorrelatorSpan span = span_for(0, very_spacing_chips);
  const auto& code = deepnav::ca_code_chips(3);
  const auto& noise = deepnav::ca_code_chips(4);
  for (auto _ : state) {
    auto sums = deepnav::correlate(kernel, x.data(), n, span, code, noise);
    benchmark::DoNotOptimize(sums);
  }
  set_rate(state, n);
}

void twelve_channels(benchmark::State& state, deepnav::CorrelatorKernel kernel, bool noise_tap) {
  const int n = 4092, channels = 12;
  const auto x = samples(n);
  for (auto _ : state) {
    for (int c = 0; c < channels; ++c) {
      auto sums = deepnav::correlate(kernel, x.data(), n, span_for(c, 0.0, noise_tap), deepnav::ca_code_chips(1 + c),
                                     deepnav::ca_code_chips(32 - c));
      benchmark::DoNotOptimize(sums);
    }
  }
  set_rate(state, static_cast<double>(n) * channels);
}

const bool registered = [] {
  for (deepnav::CorrelatorKernel k : deepnav::available_correlator_kernels()) {
    const std::string name = deepnav::correlator_kernel_name(k);
    benchmark::RegisterBenchmark(("BM_Correlate1ms/" + name).c_str(),
                                 [k](benchmark::State& s) { one_channel(s, k, 0.0); });
    benchmark::RegisterBenchmark(("BM_Correlate1msWithVeryEarlyLate/" + name).c_str(),
                                 [k](benchmark::State& s) { one_channel(s, k, 1.0); });
    benchmark::RegisterBenchmark(("BM_Correlate12Channels1ms/" + name).c_str(),
                                 [k](benchmark::State& s) { twelve_channels(s, k, true); });
    benchmark::RegisterBenchmark(("BM_Correlate12Channels1msNoNoiseTap/" + name).c_str(),
                                 [k](benchmark::State& s) { twelve_channels(s, k, false); });
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
