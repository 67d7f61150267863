#pragma once
// A synthetic single-satellite Galileo E1 OS signal for the E1 tracking and I/NAV tests: the
// composite CBOC(6,1,1/11) signal of signals/galileo (E1-B carrying a given symbol stream,
// E1-C with the CS25 secondary code), Doppler ramp, white noise with N0 = 1, complex int16
// samples, produced block by block.
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/e1_modulation.hpp"
#include "signals/sim/gaussian_noise.hpp"

namespace deepnav::testing {

struct E1SignalSpec {
  double fs_hz = 4.0e6;
  int prn = 11;
  double cn0_dbhz = 45.0;
  double doppler0_hz = 1500.0;
  double doppler_rate_hzps = 2.0;
  double code0_chips = 1000.3;  ///< unwrapped code phase at t = 0 (chips of period 0)
  double carrier0_cycles = 0.3;
  std::uint64_t seed = 5;
  /// E1-B symbol level (+1 / -1) of code period k (4 ms each); empty: all +1.
  std::function<int(std::int64_t)> symbol;
  bool secondary_code = true;  ///< false: E1-C without CS25 (a signal no channel should sync to)
};

class E1Signal {
 public:
  explicit E1Signal(E1SignalSpec spec)
      : s_(std::move(spec)),
        noise_(s_.seed + 29),
        code_b_(galileo::e1b_code_chips(s_.prn)),
        code_c_(galileo::e1c_code_chips(s_.prn)) {}

  const E1SignalSpec& spec() const { return s_; }
  /// The signal's level from the next block on (a fade, a jammer's onset).
  void set_cn0_dbhz(double cn0_dbhz) { s_.cn0_dbhz = cn0_dbhz; }
  /// Unwrapped code phase (chips) of the signal arriving at time t.
  double code_chips(double t) const {
    const double k = galileo::kE1CodeRate_cps / galileo::kE1_Hz;  // code Doppler follows the carrier's
    return s_.code0_chips + galileo::kE1CodeRate_cps * t +
           k * (s_.doppler0_hz * t + 0.5 * s_.doppler_rate_hzps * t * t);
  }
  double carrier_cycles(double t) const {
    return s_.carrier0_cycles + s_.doppler0_hz * t + 0.5 * s_.doppler_rate_hzps * t * t;
  }
  double doppler_hz(double t) const { return s_.doppler0_hz + s_.doppler_rate_hzps * t; }

  /// The next `ms` milliseconds of samples (fs a multiple of 1 kHz).
  SampleBlock next(int ms) {
    const auto per_ms = static_cast<std::size_t>(std::lround(s_.fs_hz / 1000.0));
    const std::size_t total = per_ms * static_cast<std::size_t>(ms);
    i_.assign(total, 0.0f);
    q_.assign(total, 0.0f);
    const double a = std::pow(10.0, s_.cn0_dbhz / 20.0);
    for (std::size_t m = 0; m < static_cast<std::size_t>(ms); ++m) {
      // Exact phases at each millisecond's start; a phasor rotation within it.
      const std::int64_t k0 = sample_ + static_cast<std::int64_t>(m * per_ms);
      const double t0 = static_cast<double>(k0) / s_.fs_hz, t1 = t0 + 1e-3;
      const double p0 = carrier_cycles(t0), dp = (carrier_cycles(t1) - p0) / static_cast<double>(per_ms);
      // Code phase linear within the millisecond (the Doppler rate's part is below 1e-9 chip).
      const double c0 = code_chips(t0), dc = (code_chips(t1) - c0) / static_cast<double>(per_ms);
      std::complex<double> phasor = std::polar(a, 2.0 * M_PI * (p0 - std::floor(p0)));
      const std::complex<double> rotation = std::polar(1.0, 2.0 * M_PI * dp);
      for (std::size_t j = 0; j < per_ms; ++j) {
        const double v = composite(c0 + static_cast<double>(j) * dc);
        i_[m * per_ms + j] = static_cast<float>(v * phasor.real());
        q_[m * per_ms + j] = static_cast<float>(v * phasor.imag());
        phasor *= rotation;
      }
    }
    const auto sigma = static_cast<float>(std::sqrt(s_.fs_hz / 2.0));
    noise_.add_real(i_, sigma);
    noise_.add_real(q_, sigma);
    const float scale = 64.0f / sigma;  // int16 with the noise at 64 counts RMS
    SampleBlock b;
    b.first_sample_index = sample_;
    b.samples.resize(total);
    for (std::size_t k = 0; k < total; ++k)
      b.samples[k] = {static_cast<std::int16_t>(std::lround(i_[k] * scale)),
                      static_cast<std::int16_t>(std::lround(q_[k] * scale))};
    sample_ += static_cast<std::int64_t>(total);
    return b;
  }

 private:
  double composite(double chips) {
    const double period = std::floor(chips / galileo::kE1CodeLength_chips);
    const auto chip = static_cast<std::size_t>(std::floor(chips - period * galileo::kE1CodeLength_chips));
    const auto p = static_cast<std::int64_t>(period);
    if (p != symbol_period_) {  // the symbol function may be costly: once per code period
      symbol_period_ = p;
      symbol_ = s_.symbol ? s_.symbol(p) : 1;
    }
    const int symbol = symbol_;
    const int secondary =
        s_.secondary_code ? galileo::e1c_secondary_chips()[static_cast<std::size_t>(((p % 25) + 25) % 25)] : 1;
    return galileo::e1_composite(code_b_[chip] * symbol, code_c_[chip] * secondary, chips);
  }

  E1SignalSpec s_;
  GaussianNoise noise_;
  const galileo::E1CodeChips& code_b_;
  const galileo::E1CodeChips& code_c_;
  std::int64_t sample_ = 0;
  std::int64_t symbol_period_ = -1;
  int symbol_ = 1;
  std::vector<float> i_, q_;
};

}  // namespace deepnav::testing
