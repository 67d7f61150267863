#include "signals/sim/multipath_channel.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <set>
#include <vector>

#include "signals/gps_constants.hpp"
#include "signals/sim/multipath_presets.hpp"

namespace deepnav {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;

MultipathSpec land_mobile_spec() {
  MultipathSpec m;
  m.model = MultipathSpec::Model::land_mobile;
  m.echoes = 3;
  m.echo_power_db = -10.0;
  m.mean_excess_delay_m = 30.0;
  m.echo_lifetime_s = 5.0;
  m.blocked_probability = 0.2;
  m.mean_blocked_s = 2.0;
  m.blocked_attenuation_db = 20.0;
  return m;
}

MultipathChannel constant_channel(const MultipathSpec& spec, std::uint64_t seed, std::vector<int> prns,
                                  double duration_s, double elevation_rad, double speed_mps) {
  return MultipathChannel(
      spec, seed, std::move(prns), duration_s, [=](std::size_t, double) { return elevation_rad; },
      [=](double) { return speed_mps; });
}

double wrap(double a) { return a - 2.0 * kPi * std::floor((a + kPi) / (2.0 * kPi)); }

TEST(MultipathChannel, GroundReflectionDelayAmplitudeAndPhase) {
  MultipathSpec m;
  m.model = MultipathSpec::Model::ground;
  m.antenna_height_m = 1.5;
  m.reflection_coefficient = 0.5;
  m.below_horizon_gain_db = -15.0;
  for (double el_deg : {12.0, 30.0, 60.0, 89.0}) {
    const PathSet p = ground_reflection_paths(m, el_deg * kDeg);
    ASSERT_EQ(p.echo_count, 1);
    EXPECT_EQ(p.direct_gain, 1.0);
    const double delay = 2.0 * 1.5 * std::sin(el_deg * kDeg);
    EXPECT_NEAR(p.echoes[0].excess_delay_m, delay, 1e-12) << el_deg;
    EXPECT_NEAR(p.echoes[0].amplitude, 0.5 * std::pow(10.0, -15.0 / 20.0), 1e-12) << el_deg;
    // The carrier lags by 2 pi delay / lambda plus the reflection's pi.
    EXPECT_NEAR(wrap(p.echoes[0].carrier_phase_rad - (kPi - 2.0 * kPi * delay / gps::kL1Wavelength_m)), 0.0, 1e-9);
  }
  // Near the horizon the antenna cannot reject the reflection: half the rejection at 5 deg.
  EXPECT_NEAR(ground_reflection_paths(m, 5.0 * kDeg).echoes[0].amplitude, 0.5 * std::pow(10.0, -7.5 / 20.0), 1e-12);
  EXPECT_EQ(ground_reflection_paths(m, 0.0).echo_count, 0);
  EXPECT_EQ(ground_reflection_paths(m, -0.1).echo_count, 0);
  // The relative phase turns once per wavelength of delay change: from 30 deg, the elevation
  // where 2 h sin(el) has grown by one wavelength gives the same phase again.
  const double el2 = std::asin(std::sin(30.0 * kDeg) + gps::kL1Wavelength_m / 3.0);
  EXPECT_NEAR(wrap(ground_reflection_paths(m, el2).echoes[0].carrier_phase_rad -
                   ground_reflection_paths(m, 30.0 * kDeg).echoes[0].carrier_phase_rad),
              0.0, 1e-9);
  // The channel object gives the same for the ground model, at any time.
  const MultipathChannel ch = constant_channel(m, 1, {5}, 10.0, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(ch.paths(0, 3.0, 30.0 * kDeg).echoes[0].excess_delay_m, 3.0 * std::sin(30.0 * kDeg));
}

TEST(MultipathChannel, IdealDllErrorFollowsTheClosedForm) {
  // Coherent (or envelope) E-L, infinite bandwidth, one echo of relative amplitude a, delay
  // t chips, spacing d (Kaplan & Hegarty, 2nd ed., sec. 6.3): in phase a t / (1 + a) up to
  // t = d (1 + a) / 2, then a d / 2 up to 1 - d / 2 + a d / 2, then falling linearly to 0
  // at 1 + d / 2; out of phase -a t / (1 - a) up to d (1 - a) / 2, then -a d / 2.
  const double a = 0.5, d = 0.5;
  auto in_phase = [&](double t) {
    if (t <= d * (1 + a) / 2) return a * t / (1 + a);
    if (t <= 1 - d / 2 + a * d / 2) return a * d / 2;
    if (t <= 1 + d / 2) return a * (1 + d / 2 - t) / (2 - a);
    return 0.0;
  };
  auto out_of_phase = [&](double t) {
    if (t <= d * (1 - a) / 2) return -a * t / (1 - a);
    if (t <= 1 - d / 2 - a * d / 2) return -a * d / 2;
    if (t <= 1 + d / 2) return -a * (1 + d / 2 - t) / (2 + a);
    return 0.0;
  };
  for (double t = 0.0; t <= 1.6; t += 0.05) {
    PathSet p;
    p.echo_count = 1;
    p.echoes[0].amplitude = a;
    p.echoes[0].excess_delay_m = t * kChip_m;
    p.echoes[0].carrier_phase_rad = 0.0;
    EXPECT_NEAR(ideal_dll_multipath_error_chips(p, d), in_phase(t), 1e-9) << t;
    p.echoes[0].carrier_phase_rad = -kPi;
    EXPECT_NEAR(ideal_dll_multipath_error_chips(p, d), out_of_phase(t), 1e-9) << t;
  }
  EXPECT_NEAR(ideal_dll_multipath_error_chips(PathSet{}, d), 0.0, 1e-12);  // the direct path alone
  // Direct path gone: the DLL sits on the lone echo.
  PathSet nlos;
  nlos.direct_gain = 0.0;
  nlos.echo_count = 1;
  nlos.echoes[0] = EchoPath{60.0, 0.3, 1.0, 0};
  EXPECT_NEAR(ideal_dll_multipath_error_chips(nlos, d) * kChip_m, 60.0, 1e-6);
}

TEST(MultipathChannel, LandMobileIsReproducibleAndKeyedByPrn) {
  const MultipathSpec m = land_mobile_spec();
  const MultipathChannel a = constant_channel(m, 7, {3, 5}, 60.0, 30.0 * kDeg, 10.0);
  const MultipathChannel b = constant_channel(m, 7, {3, 5}, 60.0, 30.0 * kDeg, 10.0);
  const MultipathChannel swapped = constant_channel(m, 7, {5, 3}, 60.0, 30.0 * kDeg, 10.0);
  const MultipathChannel other_seed = constant_channel(m, 8, {3, 5}, 60.0, 30.0 * kDeg, 10.0);
  int differs_by_seed = 0, differs_by_prn = 0;
  // Evaluated backwards: paths() is a pure function of (satellite, time).
  for (double t = 60.0; t >= 0.0; t -= 0.37) {
    for (std::size_t sat = 0; sat < 2; ++sat) {
      const PathSet pa = a.paths(sat, t, 0.5), pb = b.paths(sat, t, 0.5), ps = swapped.paths(1 - sat, t, 0.5);
      EXPECT_EQ(pa.direct_gain, pb.direct_gain);
      EXPECT_EQ(pa.direct_gain, ps.direct_gain);
      ASSERT_EQ(pa.echo_count, 3);
      for (int e = 0; e < 3; ++e) {
        EXPECT_EQ(pa.echoes[e].excess_delay_m, pb.echoes[e].excess_delay_m);
        EXPECT_EQ(pa.echoes[e].amplitude, pb.echoes[e].amplitude);
        EXPECT_EQ(pa.echoes[e].carrier_phase_rad, pb.echoes[e].carrier_phase_rad);
        EXPECT_EQ(pa.echoes[e].amplitude, ps.echoes[e].amplitude);
      }
      differs_by_seed += other_seed.paths(sat, t, 0.5).echoes[0].amplitude != pa.echoes[0].amplitude;
    }
    differs_by_prn += a.paths(0, t, 0.5).echoes[0].amplitude != a.paths(1, t, 0.5).echoes[0].amplitude;
  }
  EXPECT_GT(differs_by_seed, 300);
  EXPECT_GT(differs_by_prn, 150);
}

TEST(MultipathChannel, LandMobileStatisticsMatchTheSettings) {
  // 5.5 hours at 30 deg elevation and 10 m/s, sampled every 50 ms; the blockage of four
  // satellites (PRN streams), the echoes of the first.
  const MultipathSpec m = land_mobile_spec();
  const double duration = 20000.0, dt = 0.05;
  const MultipathChannel ch = constant_channel(m, 11, {9, 10, 11, 12}, duration, 30.0 * kDeg, 10.0);
  EXPECT_NEAR(MultipathChannel::blocked_share(m, 30.0 * kDeg), 0.2, 1e-12);
  long samples = 0, blocked = 0, blocked_runs = 0;
  std::array<bool, 4> was_blocked{};
  double echo_power = 0.0, echo_power2 = 0.0, delay_sum = 0.0;
  long taps = 0, echo_samples = 0;
  std::set<std::pair<int, std::uint32_t>> reflectors;
  double delay_per_reflector_sum = 0.0;
  for (double t = 0.0; t < duration; t += dt) {
    for (std::size_t sat = 0; sat < 4; ++sat) {
      const bool is_blocked = ch.blocked(sat, t);
      ++samples;
      blocked += is_blocked;
      blocked_runs += is_blocked && !was_blocked[sat];
      was_blocked[sat] = is_blocked;
    }
    const PathSet p = ch.paths(0, t, 0.5);
    EXPECT_NEAR(p.direct_gain, ch.blocked(0, t) ? 0.1 : 1.0, 1e-12);
    ++echo_samples;
    double power = 0.0;
    for (int e = 0; e < p.echo_count; ++e) {
      const double a2 = p.echoes[e].amplitude * p.echoes[e].amplitude;
      power += a2;
      echo_power2 += a2 * a2;
      delay_sum += p.echoes[e].excess_delay_m;
      ++taps;
      if (reflectors.insert({e, p.echoes[e].id}).second) delay_per_reflector_sum += p.echoes[e].excess_delay_m;
      EXPECT_GE(p.echoes[e].excess_delay_m, 0.0);
    }
    echo_power += power;
  }
  const double blocked_share = static_cast<double>(blocked) / samples;
  const double mean_blocked_s = static_cast<double>(blocked) * dt / blocked_runs;
  const double mean_echo_power = echo_power / echo_samples;
  const double tap_power = mean_echo_power / 3.0;
  // Envelope fourth moment over the squared second: 2 for Rayleigh (2 - 1/12 for 12 sinusoids).
  const double kurtosis = (echo_power2 / taps) / (tap_power * tap_power);
  const double mean_delay = delay_per_reflector_sum / static_cast<double>(reflectors.size());
  std::printf(
      "blocked share %.4f, mean blocked %.3f s over %ld periods, echo power %.2f dB, tap |h|^4 ratio %.3f, "
      "mean delay %.2f m over %zu reflectors (time-weighted %.2f m)\n",
      blocked_share, mean_blocked_s, blocked_runs, 10.0 * std::log10(mean_echo_power), kurtosis, mean_delay,
      reflectors.size(), delay_sum / taps);
  EXPECT_NEAR(blocked_share, 0.2, 0.015);
  EXPECT_NEAR(mean_blocked_s, 2.0, 0.12);
  EXPECT_NEAR(10.0 * std::log10(mean_echo_power), -10.0, 0.3);
  EXPECT_NEAR(kurtosis, 2.0, 0.15);
  EXPECT_GT(reflectors.size(), 10000u);  // 3 taps, a new reflector every 5 s
  EXPECT_NEAR(mean_delay, 30.0, 1.5);
  // Higher satellites are blocked less: 2 (1 - sin 60 deg) times the 30 deg share.
  const MultipathChannel high = constant_channel(m, 11, {9}, duration, 60.0 * kDeg, 10.0);
  long high_blocked = 0;
  for (double t = 0.0; t < duration; t += dt) high_blocked += high.blocked(0, t);
  EXPECT_NEAR(static_cast<double>(high_blocked) / echo_samples, 0.2 * 2.0 * (1.0 - std::sin(60.0 * kDeg)), 0.012);
}

TEST(MultipathChannel, FadingRateFollowsTheAntennaSpeed) {
  // For a sum of sinusoids with uniform arrival angles, E|dh/dt|^2 / E|h|^2 = (2 pi v / lambda)^2 / 2
  // (Clarke's model: the Doppler spectrum spans +-v/lambda).
  MultipathSpec m = land_mobile_spec();
  m.blocked_probability = 0.0;
  m.echo_lifetime_s = 20.0;  // many reflectors, so many sets of arrival angles
  for (double v : {2.0, 15.0}) {
    const MultipathChannel ch = constant_channel(m, 3, {4}, 4000.0, 30.0 * kDeg, v);
    const double dt = 1e-4;
    double power = 0.0, derivative = 0.0;
    for (double t = 1.0; t < 3990.0; t += 0.0731) {
      const PathSet p0 = ch.paths(0, t, 0.5), p1 = ch.paths(0, t + dt, 0.5);
      for (int e = 0; e < 3; ++e) {
        if (p0.echoes[e].id != p1.echoes[e].id) continue;  // a new reflector: no derivative
        const auto h0 = std::polar(p0.echoes[e].amplitude, p0.echoes[e].carrier_phase_rad);
        const auto h1 = std::polar(p1.echoes[e].amplitude, p1.echoes[e].carrier_phase_rad);
        power += std::norm(h0);
        derivative += std::norm((h1 - h0) / dt);
      }
    }
    const double k = 2.0 * kPi * v / gps::kL1Wavelength_m;
    std::printf("v = %.0f m/s: rms fading rate / (k v / sqrt 2) = %.3f\n", v,
                std::sqrt(derivative / power / (k * k / 2.0)));
    EXPECT_NEAR(derivative / power, k * k / 2.0, 0.1 * k * k / 2.0) << v;
  }
}

TEST(MultipathChannel, NoneGivesTheDirectPathOnly) {
  const MultipathChannel ch = constant_channel(MultipathSpec{}, 1, {1}, 10.0, 0.5, 0.0);
  const PathSet p = ch.paths(0, 1.0, 0.5);
  EXPECT_EQ(p.direct_gain, 1.0);
  EXPECT_EQ(p.echo_count, 0);
  EXPECT_FALSE(ch.blocked(0, 1.0));
}

TEST(MultipathPresets, EnvironmentsGrowHarsher) {
  EXPECT_EQ(multipath_for_environment("none").model, MultipathSpec::Model::none);
  const MultipathSpec open = multipath_for_environment("open-sky");
  EXPECT_EQ(open.model, MultipathSpec::Model::ground);
  EXPECT_NEAR(ground_reflection_paths(open, 45.0 * kDeg).echoes[0].amplitude, 0.03, 1e-3);
  const MultipathSpec sub = multipath_for_environment("suburban"), urban = multipath_for_environment("urban");
  EXPECT_EQ(sub.model, MultipathSpec::Model::land_mobile);
  EXPECT_EQ(urban.model, MultipathSpec::Model::land_mobile);
  EXPECT_LT(sub.blocked_probability, urban.blocked_probability);
  EXPECT_LT(sub.echo_power_db, urban.echo_power_db);
  EXPECT_LT(sub.mean_excess_delay_m, urban.mean_excess_delay_m);
  EXPECT_LT(sub.blocked_attenuation_db, urban.blocked_attenuation_db);
  EXPECT_EQ(multipath_environments().size(), 4u);
  for (const auto& name : multipath_environments()) EXPECT_NO_THROW(multipath_for_environment(name));
  EXPECT_THROW(multipath_for_environment("canyon"), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
