#include "signals/sim/satellite_signal_kernel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace deepnav {
namespace {

// Direct evaluation of the same signal in double precision: the reference the fast kernel
// (fixed-point code index, float phasor rotation) must reproduce.
void reference_segment(std::vector<double>& i_out, std::vector<double>& q_out, const SignalSegment& s,
                       const CaCodeChips& code) {
  for (std::size_t k = 0; k < i_out.size(); ++k) {
    const double chip = std::fmod(s.code_phase_chips + static_cast<double>(k) * s.code_step_chips, 1023.0);
    const double level = s.amplitude * code[static_cast<int>(chip)];
    const double phase = 2.0 * M_PI * (s.carrier_phase_cycles + static_cast<double>(k) * s.carrier_step_cycles);
    i_out[k] += level * std::cos(phase);
    q_out[k] += level * std::sin(phase);
  }
}

TEST(SatelliteSignalKernel, MatchesDirectEvaluationOverOneMillisecond) {
  const int n = 4092;
  SignalSegment s;
  s.carrier_phase_cycles = 12345.678;
  s.carrier_step_cycles = (3000.0 + 1234.5) / 4.092e6;
  s.code_phase_chips = 1000.25;  // wraps inside the block
  s.code_step_chips = 1.023e6 * (1.0 + 1234.5 / 1575.42e6) / 4.092e6;
  s.amplitude = 3.0f;
  std::vector<float> i(n, 0.5f), q(n, -0.5f), scratch(n);
  add_satellite_segment(i.data(), q.data(), n, s, ca_code_chips(7), scratch.data());
  std::vector<double> ri(n, 0.5), rq(n, -0.5);
  reference_segment(ri, rq, s, ca_code_chips(7));
  int chip_mismatch = 0;
  for (int k = 0; k < n; ++k) {
    const double err = std::hypot(i[k] - ri[k], q[k] - rq[k]);
    // A sample right on a chip edge may land on either side in fixed point; anything else
    // must agree to float precision (phasor drift over 4092 samples stays ~1e-5 rad).
    if (err > 1e-3) {
      ++chip_mismatch;
    } else {
      EXPECT_LT(err, 3.0 * 5e-5) << "sample " << k;
    }
  }
  EXPECT_LE(chip_mismatch, 2);
}

TEST(SatelliteSignalKernel, AddsToExistingSamplesAndHandlesShortTail) {
  for (int n : {1, 15, 16, 17, 33}) {
    SignalSegment s;
    s.carrier_step_cycles = 0.1;
    s.code_step_chips = 0.25;
    s.amplitude = 1.0f;
    std::vector<float> i(n, 1.0f), q(n, 0.0f), scratch(n);
    add_satellite_segment(i.data(), q.data(), n, s, ca_code_chips(1), scratch.data());
    std::vector<double> ri(n, 1.0), rq(n, 0.0);
    reference_segment(ri, rq, s, ca_code_chips(1));
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(i[k], ri[k], 1e-5) << n << " " << k;
      EXPECT_NEAR(q[k], rq[k], 1e-5) << n << " " << k;
    }
  }
}

TEST(SatelliteSignalKernel, StepsThatCouldNeverReachTheCodeEndAreErrors) {
  // A code step of zero, NaN, a negative one, or one of a whole code period per sample or
  // more (an absurd range rate) once made the code fill loop spin forever.
  for (double step : {0.0, -0.25, std::nan(""), 1023.0, 1e30, 1e-12}) {
    SignalSegment s;
    s.code_step_chips = step;
    s.amplitude = 1.0f;
    std::vector<float> i(64), q(64), scratch(64);
    EXPECT_THROW(add_satellite_segment(i.data(), q.data(), 64, s, ca_code_chips(1), scratch.data()),
                 std::invalid_argument)
        << step;
  }
  SignalSegment s;
  s.code_step_chips = 0.25;
  s.code_phase_chips = std::nan("");
  std::vector<float> i(64), q(64), scratch(64);
  EXPECT_THROW(add_satellite_segment(i.data(), q.data(), 64, s, ca_code_chips(1), scratch.data()),
               std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
