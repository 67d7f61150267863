#include "tools/bench/correlator_throughput.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdint>
#include <random>
#include <vector>

#include "signals/galileo/e1_codes.hpp"
#include "signals/gps_constants.hpp"
#include "tools/bench/process_usage.hpp"

namespace deepnav::bench {

CorrelatorThroughput correlator_throughput(CorrelatorKernel kernel, bool noise_tap) {
  const int n = 4092;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> level(-7, 7);
  std::vector<Sample> samples(static_cast<std::size_t>(n));
  for (auto& x : samples) x = Sample(static_cast<std::int16_t>(level(rng)), static_cast<std::int16_t>(level(rng)));
  // As the receiver calls it: the block's magnitude scan and planar copy made once, outside the timing.
  std::vector<std::int16_t> i(samples.size()), q(samples.size());
  deinterleave(samples.data(), n, i.data(), q.data());
  const CorrelatorInput input{samples.data(), i.data(), q.data()};
  std::vector<CorrelatorSpan> spans(12);
  for (int c = 0; c < 12; ++c) {
    spans[static_cast<std::size_t>(c)].magnitude_bits = sample_magnitude_bits(samples.data(), n);
    spans[static_cast<std::size_t>(c)].carrier_step_cycles = (1000.0 * c - 5000.0) / 4.092e6;
    spans[static_cast<std::size_t>(c)].code_phase_chips = 85.3 * c;
    spans[static_cast<std::size_t>(c)].code_step_chips = gps::kCodeRate_cps / 4.092e6 * (1.0 + 1e-6 * c);
    spans[static_cast<std::size_t>(c)].noise_tap = noise_tap;
  }
  double sink = 0.0;
  long long calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu_s();
  while (seconds_since(t0) < 1.0) {
    for (int c = 0; c < 12; ++c) {
      const CorrelatorSums r =
          correlate(kernel, input, n, spans[static_cast<std::size_t>(c)], ca_code_chips(c + 1), ca_code_chips(32));
      sink += r.prompt.real();
      ++calls;
    }
  }
  const double wall = seconds_since(t0), cpu = thread_cpu_s() - c0;
  if (sink == 1e300) fmt::print("{}", sink);  // keeps the work observable
  return {wall, cpu, static_cast<double>(calls) * n};
}

CorrelatorThroughput e1_correlator_throughput(std::optional<CorrelatorKernel> kernel, bool noise_tap) {
  constexpr double kFs = 4.0e6;
  constexpr int kChannels = 8;
  const int n = 16000;  // one 4 ms code period
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> level(-7, 7);
  std::vector<Sample> samples(static_cast<std::size_t>(n));
  for (auto& x : samples) x = Sample(static_cast<std::int16_t>(level(rng)), static_cast<std::int16_t>(level(rng)));
  std::vector<std::int16_t> i(samples.size()), q(samples.size());
  deinterleave(samples.data(), n, i.data(), q.data());
  const CorrelatorInput input{samples.data(), i.data(), q.data()};
  std::vector<E1CorrelatorSpan> spans(kChannels);
  std::vector<E1CorrelatorCodes> codes(kChannels);
  for (int c = 0; c < kChannels; ++c) {
    E1CorrelatorSpan& s = spans[static_cast<std::size_t>(c)];
    s.magnitude_bits = sample_magnitude_bits(samples.data(), n);
    s.carrier_step_cycles = (1000.0 * c - 4000.0) / kFs;
    s.code_phase_chips = 411.7 * c;
    s.code_step_chips = galileo::kE1CodeRate_cps / kFs * (1.0 + 1e-6 * c);
    s.noise_tap = noise_tap;
    const int prn = 2 * c + 1;
    codes[static_cast<std::size_t>(c)] = {&galileo::e1c_code_chips(prn), &galileo::e1b_code_chips(prn),
                                          &galileo::e1c_code_chips(prn + 1)};
  }
  double sink = 0.0;
  long long calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu_s();
  while (seconds_since(t0) < 1.0) {
    for (int c = 0; c < kChannels; ++c) {
      const auto& s = spans[static_cast<std::size_t>(c)];
      const auto& code = codes[static_cast<std::size_t>(c)];
      const E1CorrelatorSums r =
          kernel ? correlate_e1(*kernel, input, n, s, code) : correlate_e1_reference(samples.data(), n, s, code);
      sink += r.prompt.real();
      ++calls;
    }
  }
  const double wall = seconds_since(t0), cpu = thread_cpu_s() - c0;
  if (sink == 1e300) fmt::print("{}", sink);  // keeps the work observable
  return {wall, cpu, static_cast<double>(calls) * n};
}

}  // namespace deepnav::bench
