#pragma once
// Data-bit synchronisation from 1 ms prompts. For each of the 20 candidate bit edges the
// metric is the mean over bits of |sum of the bit's 20 prompts|: at the true edge no bit
// sum contains a data transition, at an edge off by m ms every transition (half the bits)
// costs 2 m ms of amplitude. Unlike counting sign changes of the 1 ms prompts (whose
// single-millisecond sign errors swamp the votes below about 35 dB-Hz) this integrates
// coherently over each bit, and the magnitude makes it insensitive to the carrier phase.
// The edge is declared once the best candidate leads the runner-up by `z` standard
// deviations of that lead, the noise level coming from the noise correlator.
#include <array>
#include <complex>
#include <cstdint>
#include <optional>

namespace deepnav {

class BitSynchronizer {
 public:
  explicit BitSynchronizer(int min_bits = 20, double z = 5.0);
  /// Adds the 1 ms prompt and noise correlator of code period `period` (periods counted from
  /// any origin; a jump in the count starts over). Returns the edge, as the period count
  /// modulo 20 at which bits start, once decided.
  std::optional<int> add(std::int64_t period, const std::complex<double>& prompt, const std::complex<double>& noise);
  void reset();
  int bits_seen() const;

 private:
  int min_bits_;
  double z_;
  std::optional<std::int64_t> last_period_;
  std::array<std::complex<double>, 20> partial_{};
  std::array<int, 20> partial_ms_{};
  std::array<double, 20> metric_{};
  std::array<int, 20> bits_{};
  double noise_power_ = 0.0;
  int noise_count_ = 0;
};

}  // namespace deepnav
