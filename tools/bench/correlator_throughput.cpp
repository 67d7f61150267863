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
namespace {

/// n samples of 4-bit noise, with the block's planar copy made once, outside the timing, as
/// the receiver prepares a block for all its channels.
struct NoiseBlock {
  std::vector<Sample> samples;
  std::vector<std::int16_t> i, q;
  int magnitude_bits = 0;
  NoiseBlock(int n, unsigned seed) : samples(static_cast<std::size_t>(n)), i(samples.size()), q(samples.size()) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> level(-7, 7);
    for (auto& x : samples) x = Sample(static_cast<std::int16_t>(level(rng)), static_cast<std::int16_t>(level(rng)));
    deinterleave(samples.data(), n, i.data(), q.data());
    magnitude_bits = sample_magnitude_bits(samples.data(), n);
  }
  CorrelatorInput input() const { return {samples.data(), i.data(), q.data()}; }
};

/// Calls `correlate_channel(c)` (returning the prompt's real part) for every channel in turn
/// for about a second; the figures of n samples a call.
template <typename CorrelateChannel>
CorrelatorThroughput timed(int channels, int n, CorrelateChannel correlate_channel) {
  double sink = 0.0;
  long long calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = thread_cpu_s();
  while (seconds_since(t0) < 1.0) {
    for (int c = 0; c < channels; ++c) {
      sink += correlate_channel(c);
      ++calls;
    }
  }
  const double wall = seconds_since(t0), cpu = thread_cpu_s() - c0;
  if (sink == 1e300) fmt::print("{}", sink);  // keeps the work observable
  return {wall, cpu, static_cast<double>(calls) * n};
}

}  // namespace

CorrelatorThroughput correlator_throughput(CorrelatorKernel kernel, bool noise_tap) {
  constexpr double kFs = 4.092e6;
  constexpr int kChannels = 12;
  const int n = 4092;
  const NoiseBlock block(n, 5);
  const CorrelatorInput input = block.input();
  std::vector<CorrelatorSpan> spans(kChannels);
  for (int c = 0; c < kChannels; ++c) {
    CorrelatorSpan& s = spans[static_cast<std::size_t>(c)];
    s.magnitude_bits = block.magnitude_bits;
    s.carrier_step_cycles = (1000.0 * c - 5000.0) / kFs;
    s.code_phase_chips = 85.3 * c;
    s.code_step_chips = gps::kCodeRate_cps / kFs * (1.0 + 1e-6 * c);
    s.noise_tap = noise_tap;
  }
  return timed(kChannels, n, [&](int c) {
    return correlate(kernel, input, n, spans[static_cast<std::size_t>(c)], ca_code_chips(c + 1), ca_code_chips(32))
        .prompt.real();
  });
}

CorrelatorThroughput e1_correlator_throughput(std::optional<CorrelatorKernel> kernel, bool noise_tap) {
  constexpr double kFs = 4.0e6;
  constexpr int kChannels = 8;
  const int n = 16000;  // one 4 ms code period
  const NoiseBlock block(n, 7);
  const CorrelatorInput input = block.input();
  std::vector<E1CorrelatorSpan> spans(kChannels);
  std::vector<E1CorrelatorCodes> codes(kChannels);
  for (int c = 0; c < kChannels; ++c) {
    E1CorrelatorSpan& s = spans[static_cast<std::size_t>(c)];
    s.magnitude_bits = block.magnitude_bits;
    s.carrier_step_cycles = (1000.0 * c - 4000.0) / kFs;
    s.code_phase_chips = 411.7 * c;
    s.code_step_chips = galileo::kE1CodeRate_cps / kFs * (1.0 + 1e-6 * c);
    s.noise_tap = noise_tap;
    const int prn = 2 * c + 1;
    codes[static_cast<std::size_t>(c)] = {&galileo::e1c_code_chips(prn), &galileo::e1b_code_chips(prn),
                                          &galileo::e1c_code_chips(prn + 1)};
  }
  return timed(kChannels, n, [&](int c) {
    const auto& s = spans[static_cast<std::size_t>(c)];
    const auto& code = codes[static_cast<std::size_t>(c)];
    return (kernel ? correlate_e1(*kernel, input, n, s, code)
                   : correlate_e1_reference(block.samples.data(), n, s, code))
        .prompt.real();
  });
}

}  // namespace deepnav::bench
