// The code-multipath error envelope of the receiver's DLL, measured on samples made by
// the synthesizer's own kernel: direct signal plus one echo of relative amplitude alpha
// and delay tau, in phase and out of phase, noise-free. The error is the replica offset
// at which the receiver's discriminator (dll_code_error_chips: the normalised
// early-minus-late envelope (|E| - |L|) / (|E| + |L|) (1 - d/2), on the correlator's E and
// L taps at +-d/2) is zero, found by bisection. For an echo in phase or out of phase the
// composite correlation is real and positive at both taps, so the envelope's zero is the
// coherent E-L zero and the literature's coherent envelope applies exactly (for other
// phases it is the same to first order in alpha). Samples at 40 Msps (39.1 per chip, not
// a whole number, so the sampled correlation is the triangle) stand for infinite bandwidth.
//
// Closed form (Braasch; Kaplan & Hegarty, Understanding GPS, 2nd ed., sec. 6.3), error in
// chips, positive when the measured range is too long, for spacing d <= 1 and alpha < 1:
//   in phase:      alpha tau / (1 + alpha)                  tau <= d (1 + alpha) / 2
//                  alpha d / 2                              ... <= 1 - d/2 + alpha d / 2
//                  alpha (1 + d/2 - tau) / (2 - alpha)      ... <= 1 + d/2, then 0
//   out of phase: -alpha tau / (1 - alpha)                  tau <= d (1 - alpha) / 2
//                 -alpha d / 2                              ... <= 1 - d/2 - alpha d / 2
//                 -alpha (1 + d/2 - tau) / (2 + alpha)      ... <= 1 + d/2, then 0
// So the peak is alpha d / 2 chips: 0.125 chip (36.6 m) for alpha = 0.5, d = 0.5.
//
// The closed form assumes an ideal code, whose correlation is zero beyond one chip. A C/A
// code's periodic autocorrelation at whole-chip offsets k != 0 is -1, -65 or +63 over 1023,
// and between them the sampled correlation is linear: where an echo's taps fall on a
// sloping stretch the DLL keeps a residual error of about alpha s d / 2 for a slope s per
// chip, up to 6 % of the peak. PRN 1's autocorrelation is -1/1023 at offsets 1 to 4 chips,
// so it shows the textbook envelope; PRN 7 (+63 at one chip) shows the residual.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "receiver/tracking/correlator.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/multipath_channel.hpp"
#include "signals/sim/satellite_signal_kernel.hpp"

namespace deepnav {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;
constexpr double kFs = 40e6;
constexpr int kSamples = 40000;  // one code period
constexpr double kCodeStep = gps::kCodeRate_cps / kFs;
constexpr double kCodePhase0 = 300.37;

double closed_form(double alpha, double d, double tau, bool in_phase) {
  if (in_phase) {
    if (tau <= d * (1 + alpha) / 2) return alpha * tau / (1 + alpha);
    if (tau <= 1 - d / 2 + alpha * d / 2) return alpha * d / 2;
    if (tau <= 1 + d / 2) return alpha * (1 + d / 2 - tau) / (2 - alpha);
    return 0.0;
  }
  if (tau <= d * (1 - alpha) / 2) return -alpha * tau / (1 - alpha);
  if (tau <= 1 - d / 2 - alpha * d / 2) return -alpha * d / 2;
  if (tau <= 1 + d / 2) return -alpha * (1 + d / 2 - tau) / (2 + alpha);
  return 0.0;
}

/// Direct signal plus one echo, made with the synthesizer's kernel and stored as the int16
/// samples the receiver reads.
std::vector<Sample> direct_plus_echo(int prn, double alpha, double tau_chips, double phase_rad) {
  constexpr float kAmplitude = 12000.0f;  // |direct + echo| < 2^15
  std::vector<float> i(kSamples, 0.0f), q(kSamples, 0.0f), scratch(kSamples);
  SignalSegment direct;
  direct.code_phase_chips = kCodePhase0;
  direct.code_step_chips = kCodeStep;
  direct.amplitude = kAmplitude / (1.0f + static_cast<float>(alpha));
  add_satellite_segment(i.data(), q.data(), kSamples, direct, ca_code_chips(prn), scratch.data());
  SignalSegment echo = direct;
  echo.code_phase_chips = std::fmod(kCodePhase0 - tau_chips + 1023.0, 1023.0);  // arrives tau chips later
  echo.carrier_phase_cycles = phase_rad / (2.0 * kPi);
  echo.amplitude = direct.amplitude * static_cast<float>(alpha);
  add_satellite_segment(i.data(), q.data(), kSamples, echo, ca_code_chips(prn), scratch.data());
  std::vector<Sample> out(kSamples);
  for (int k = 0; k < kSamples; ++k)
    out[k] = Sample(static_cast<std::int16_t>(std::lround(i[k])), static_cast<std::int16_t>(std::lround(q[k])));
  return out;
}

/// The receiver's discriminator with the replica `offset_chips` ahead of the direct signal's code.
double discriminator(int prn, const std::vector<Sample>& x, double offset_chips, double spacing_chips) {
  CorrelatorSpan span;
  span.code_phase_chips = kCodePhase0 + offset_chips;
  span.code_step_chips = kCodeStep;
  span.spacing_chips = spacing_chips;
  const CorrelatorSums s = correlate(x.data(), kSamples, span, ca_code_chips(prn), ca_code_chips(prn % 32 + 1));
  return dll_code_error_chips(s.early, s.late, spacing_chips);
}

/// Where the discriminator is zero (chips, positive: range too long). The lock point lies
/// within +-d/2 of the direct path's (|error| <= alpha d / 2 < d / 2), where the
/// discriminator goes from negative (replica ahead: late tap stronger) to positive.
double lock_point_chips(double alpha, double tau_chips, double phase_rad, double spacing_chips, int prn) {
  const std::vector<Sample> x = direct_plus_echo(prn, alpha, tau_chips, phase_rad);
  double behind = -0.5 * spacing_chips, ahead = 0.5 * spacing_chips;  // replica offsets
  EXPECT_GT(discriminator(prn, x, behind, spacing_chips), 0.0);
  EXPECT_LT(discriminator(prn, x, ahead, spacing_chips), 0.0);
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (behind + ahead);
    (discriminator(prn, x, mid, spacing_chips) > 0.0 ? behind : ahead) = mid;
  }
  // A replica behind the direct code (negative offset) measures a later arrival: a longer range.
  return -0.5 * (behind + ahead);
}

/// The multipath error: the lock point's shift from where the direct signal alone puts it.
/// (Alone it is off by a few 1e-4 chip: the chip edges the code actually has fall at
/// sample offsets that do not average to exactly half a sample, a sampling effect of any
/// code phase, not multipath.)
double tracking_error_chips(double alpha, double tau_chips, double phase_rad, double spacing_chips, int prn = 1) {
  return lock_point_chips(alpha, tau_chips, phase_rad, spacing_chips, prn) -
         lock_point_chips(0.0, 0.0, 0.0, spacing_chips, prn);
}

struct Envelope {
  std::vector<double> tau, in_phase, out_of_phase;
};

Envelope measure(double alpha, double d, double tau_max, double tau_step) {
  Envelope e;
  for (int k = 0; k * tau_step <= tau_max + 1e-9; ++k) {
    const double tau = k * tau_step;
    e.tau.push_back(tau);
    e.in_phase.push_back(tracking_error_chips(alpha, tau, 0.0, d));
    e.out_of_phase.push_back(tracking_error_chips(alpha, tau, kPi, d));
  }
  return e;
}

void check_envelope(double alpha, double d_nominal, double tau_step) {
  // The correlator places its taps on a 2^-11 chip grid: the spacing it really uses.
  const double d = 2.0 * std::round(0.5 * d_nominal * 2048.0) / 2048.0;
  const Envelope e = measure(alpha, d_nominal, 1.5, tau_step);
  const double peak = alpha * d / 2.0;
  double max_in = 0.0, min_out = 0.0, tau_max_in = 0.0, tau_min_out = 0.0;
  std::printf("d = %.2f chip, alpha = %.2f: tau (chips)  in phase (chips, m)  out of phase (chips, m)\n", d_nominal,
              alpha);
  for (std::size_t k = 0; k < e.tau.size(); ++k) {
    const double tau = e.tau[k], ip = e.in_phase[k], op = e.out_of_phase[k];
    if (ip > max_in) {
      max_in = ip;
      tau_max_in = tau;
    }
    if (op < min_out) {
      min_out = op;
      tau_min_out = tau;
    }
    if (k % static_cast<std::size_t>(std::lround(0.05 / tau_step)) == 0)
      std::printf("  %.3f  %+.5f %+7.3f  %+.5f %+7.3f\n", tau, ip, ip * kChip_m, op, op * kChip_m);
    // The closed form everywhere, to a few per cent of the peak.
    EXPECT_NEAR(ip, closed_form(alpha, d, tau, true), 0.03 * peak) << "in phase, tau " << tau;
    EXPECT_NEAR(op, closed_form(alpha, d, tau, false), 0.03 * peak) << "out of phase, tau " << tau;
    // The ideal-DLL truth the synthesizer writes (sat_truth.csv multipath_m) agrees.
    PathSet p;
    p.echo_count = 1;
    p.echoes[0] = EchoPath{tau * kChip_m, alpha, 0.0, 0};
    EXPECT_NEAR(ip, ideal_dll_multipath_error_chips(p, d), 0.03 * peak) << tau;
    // Small delays: the linear rise, within 20 %, and monotone.
    if (tau > 0.0 && tau <= 0.8 * d * (1 + alpha) / 2) {
      EXPECT_NEAR(ip, alpha * tau / (1 + alpha), 0.2 * alpha * tau / (1 + alpha)) << tau;
      EXPECT_GT(ip, e.in_phase[k - 1]) << tau;
    }
    if (tau > 0.0 && tau <= 0.8 * d * (1 - alpha) / 2) {
      EXPECT_NEAR(op, -alpha * tau / (1 - alpha), 0.2 * alpha * tau / (1 - alpha)) << tau;
    }
    // Opposite signs while the echo overlaps the taps; nothing beyond 1 + d/2.
    if (tau > 0.02 && tau < 1.0 + d / 2 - 0.02) {
      EXPECT_GT(ip, 0.0) << tau;
      EXPECT_LT(op, 0.0) << tau;
    }
    if (tau > 1.0 + d / 2 + 0.01) {
      EXPECT_LT(std::abs(ip), 0.03 * peak) << tau;
      EXPECT_LT(std::abs(op), 0.03 * peak) << tau;
    }
  }
  std::printf(
      "  peak in phase %+.5f chip (%+.2f m) at tau %.3f; out of phase %+.5f chip (%+.2f m) at tau %.3f; "
      "alpha d / 2 = %.5f chip (%.2f m)\n",
      max_in, max_in * kChip_m, tau_max_in, min_out, min_out * kChip_m, tau_min_out, peak, peak * kChip_m);
  EXPECT_NEAR(max_in, peak, 0.05 * peak);
  EXPECT_NEAR(min_out, -peak, 0.05 * peak);
  // The peak is reached at d (1 +- alpha) / 2 and held over the plateau.
  EXPECT_GE(tau_max_in, d * (1 + alpha) / 2 - 2 * tau_step);
  EXPECT_LE(tau_max_in, 1.0 - d / 2 + alpha * d / 2 + 2 * tau_step);
  EXPECT_GE(tau_min_out, d * (1 - alpha) / 2 - 2 * tau_step);
  EXPECT_LE(tau_min_out, 1.0 - d / 2 - alpha * d / 2 + 2 * tau_step);
}

TEST(MultipathEnvelope, WideCorrelatorHalfChip) { check_envelope(0.5, 0.5, 0.025); }

TEST(MultipathEnvelope, NarrowCorrelatorTenthChip) { check_envelope(0.5, 0.1, 0.01); }

TEST(MultipathEnvelope, CodeSidelobesLeaveASmallResidualBeyondTheTriangle) {
  // PRN 7: R(1 chip) = +63/1023, R(2..4 chips) = -1/1023, so between 1 and 2 chips the
  // correlation slopes by s = -64/1023 per chip: an echo whose taps both lie there pulls the
  // DLL by about alpha |s| d / 2 = 0.0078 chip (2.3 m), same sign as the echo.
  const double alpha = 0.5, d = 0.5, s = 64.0 / 1023.0;
  for (double tau : {1.3, 1.4}) {
    const double in_phase = tracking_error_chips(alpha, tau, 0.0, d, 7);
    const double out_of_phase = tracking_error_chips(alpha, tau, kPi, d, 7);
    std::printf("PRN 7, tau %.2f chip: %+.5f / %+.5f chip in / out of phase\n", tau, in_phase, out_of_phase);
    EXPECT_NEAR(in_phase, alpha * s * d / 2, 0.2 * alpha * s * d / 2) << tau;
    EXPECT_NEAR(out_of_phase, -alpha * s * d / 2, 0.2 * alpha * s * d / 2) << tau;
  }
}

TEST(MultipathEnvelope, EchoFarBeyondTheTriangleChangesNothing) {
  // PRN 1's autocorrelation is -1/1023 from 1 to 4 chips: nothing to pull the DLL.
  EXPECT_NEAR(tracking_error_chips(0.5, 3.0, 0.0, 0.5), 0.0, 0.01 * 0.125);
  EXPECT_NEAR(tracking_error_chips(0.5, 3.0, kPi, 0.5), 0.0, 0.01 * 0.125);
}

}  // namespace
}  // namespace deepnav
