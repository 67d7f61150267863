#pragma once
// Finding the phase of the CS25 secondary code on a Galileo E1-C channel from consecutive
// 4 ms pilot prompts, before the carrier phase is known.
//
// Each pair of consecutive prompts gives d_k = p_k conj(p_(k-1)) = |A|^2 c_k c_(k-1)
// e^(j 2 pi df T): the carrier phase cancels and a residual frequency error df only turns
// it a little (under 90 degrees while |df| < 62 Hz). For each of the 25 phases the real part
// of sum_k d_k c_k c_(k-1) is formed; CS25's differential sequence has periodic sidelobes of
// at most 5 against 25 in that positive sense, so a window of two code periods (50 prompts)
// whose best phase beats the runner-up by a wide margin and holds at least half the products'
// magnitude sum names the phase reliably at 35 dB-Hz and is rarely fooled by noise.
// The sign of the secondary-wiped coherent sum then says on which side of its Costas
// ambiguity the carrier loop sits.
#include <complex>
#include <cstdint>
#include <deque>
#include <optional>

namespace deepnav {

struct SecondaryCodePhase {
  /// Code period p (the channel's count) carries CS25 chip (p + offset) mod 25.
  int offset = 0;
  /// Sign (+1/-1) of the real part of the secondary-wiped pilot prompts over the window.
  int prompt_sign = 1;
};

class SecondaryCodeSynchronizer {
 public:
  /// window_periods: at least 26 (25 differential products) prompts; margin: how many times
  /// the best score must exceed the runner-up. Throws std::invalid_argument otherwise.
  explicit SecondaryCodeSynchronizer(int window_periods = 50, double margin = 2.5);
  /// The pilot prompt of code period `period`. A period that does not follow the previous
  /// one starts the window afresh. Returns the phase once the window is full and decisive.
  std::optional<SecondaryCodePhase> add(std::int64_t period, const std::complex<double>& prompt);
  void reset() { prompts_.clear(); }

 private:
  int window_;
  double margin_;
  std::deque<std::complex<double>> prompts_;
  std::int64_t last_period_ = 0;
};

/// CS25 chip (+1/-1) of code period `period` for a synchronised `offset`.
int secondary_chip(std::int64_t period, int offset);

}  // namespace deepnav
