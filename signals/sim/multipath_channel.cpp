#include "signals/sim/multipath_channel.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>

#include "signals/gps_constants.hpp"
#include "signals/sim/gaussian_noise.hpp"

namespace deepnav {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;

/// Below this elevation the antenna's rejection of the ground reflection fades out: the
/// direct ray at +el and the reflected one at -el become indistinguishable at the horizon.
constexpr double kRejectionRampElevation_rad = 10.0 * kDegToRad;

/// Sinusoids per fading tap: with random arrival angles a dozen give a Rayleigh envelope
/// to within a few per cent in the body of the distribution.
constexpr int kFadingSinusoids = 12;
/// The distance travelled is integrated on this grid and interpolated linearly.
constexpr double kDistanceStep_s = 0.1;
/// Moving scatterers (traffic, foliage) keep the echoes fading at a standstill: the
/// pattern is driven through at least this fast (Doppler spread 1.6 Hz at L1).
constexpr double kFadingSpeedFloor_mps = 0.3;
/// The blockage rate follows the elevation, re-evaluated this often (the exponential
/// sojourns are memoryless, so redrawing at each step is exact for a stepwise rate).
constexpr double kBlockageRateStep_s = 10.0;
constexpr double kMaxBlockedShare = 0.95;

/// Stream tags, so that no two uses of (seed, PRN, ...) share random numbers.
constexpr std::uint64_t kTagBlockage = 0x426C6F636BULL;  // "Block"
constexpr std::uint64_t kTagTapPhase = 0x5461705068ULL;  // "TapPh"
constexpr std::uint64_t kTagTap = 0x5461702047ULL;       // "Tap G"

std::uint64_t mix(std::uint64_t a, std::uint64_t b) { return splitmix64(a ^ splitmix64(b + 0x9E3779B97F4A7C15ULL)); }

/// Uniform in [0, 1) from the top 53 bits.
double uniform(Xoshiro256ss& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
/// Exponential with unit mean (1 - u is in (0, 1], so the log is finite).
double exponential(Xoshiro256ss& rng) { return -std::log(1.0 - uniform(rng)); }

double wrap_pi(double a) { return a - 2.0 * kPi * std::floor((a + kPi) / (2.0 * kPi)); }

/// The C/A autocorrelation of an infinitely wide band: a triangle of one chip half-width.
double triangle(double x_chips) { return std::max(0.0, 1.0 - std::abs(x_chips)); }

}  // namespace

PathSet ground_reflection_paths(const MultipathSpec& spec, double elevation_rad) {
  PathSet p;
  if (elevation_rad <= 0.0) return p;
  const double delay_m = 2.0 * spec.antenna_height_m * std::sin(elevation_rad);
  const double rejection_db = spec.below_horizon_gain_db * std::min(1.0, elevation_rad / kRejectionRampElevation_rad);
  EchoPath& e = p.echoes[0];
  e.excess_delay_m = delay_m;
  e.amplitude = spec.reflection_coefficient * std::pow(10.0, rejection_db / 20.0);
  // The reflected carrier lags by its extra path plus the reflection's half cycle.
  e.carrier_phase_rad = wrap_pi(kPi - 2.0 * kPi * delay_m / gps::kL1Wavelength_m);
  e.id = 0;
  p.echo_count = 1;
  return p;
}

double ideal_dll_multipath_error_chips(const PathSet& paths, double spacing_chips) {
  // Composite correlation at replica delay x (chips, positive later than the direct path).
  auto composite = [&](double x) {
    std::complex<double> c = paths.direct_gain * triangle(x);
    for (int i = 0; i < paths.echo_count; ++i) {
      const EchoPath& e = paths.echoes[static_cast<std::size_t>(i)];
      c += std::polar(e.amplitude, e.carrier_phase_rad) * triangle(x - e.excess_delay_m / kChip_m);
    }
    return std::abs(c);
  };
  double last_chips = 0.0;
  for (int i = 0; i < paths.echo_count; ++i)
    last_chips = std::max(last_chips, paths.echoes[static_cast<std::size_t>(i)].excess_delay_m / kChip_m);
  // The DLL sits on the discriminator zero next to the strongest correlation peak. With
  // the peak x* found on a grid whose step divides the spacing, D(x) = |C(x - d/2)| -
  // |C(x + d/2)| is <= 0 at x* - d/2 and >= 0 at x* + d/2: a bracket for bisection.
  const double d = spacing_chips;
  const double step = d / 20.0;
  const double lo = -1.0 - d, hi = last_chips + 1.0 + d;
  double best_x = 0.0, best = 0.0;
  const auto points = static_cast<int>(std::ceil((hi - lo) / step));
  for (int i = 0; i <= points; ++i) {
    const double x = lo + i * step;
    const double c = composite(x);
    if (c > best) {
      best = c;
      best_x = x;
    }
  }
  if (best <= 0.0) return 0.0;
  auto disc = [&](double x) { return composite(x - 0.5 * d) - composite(x + 0.5 * d); };
  double a = best_x - 0.5 * d, b = best_x + 0.5 * d;
  for (int it = 0; it < 60; ++it) {
    const double m = 0.5 * (a + b);
    (disc(m) < 0.0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

double MultipathChannel::blocked_share(const MultipathSpec& spec, double elevation_rad) {
  const double scale = 2.0 * (1.0 - std::sin(std::clamp(elevation_rad, 0.0, kPi / 2.0)));
  return std::min(kMaxBlockedShare, spec.blocked_probability * scale);
}

MultipathChannel::MultipathChannel(const MultipathSpec& spec, std::uint64_t seed, std::vector<int> prns,
                                   double duration_s, const ElevationFn& elevation_rad, const SpeedFn& speed_mps)
    : spec_(spec), seed_(splitmix64(seed ^ 0x4D756C7469706174ULL)), prns_(std::move(prns)) {
  if (spec_.echoes < 0 || spec_.echoes > MultipathSpec::kMaxEchoes)
    throw std::invalid_argument("multipath: echoes must be 0.." + std::to_string(MultipathSpec::kMaxEchoes));
  if (spec_.model != MultipathSpec::Model::land_mobile) return;
  const double end_s = duration_s + 1.0;

  // Blockage: alternating exponential sojourns. The blocked mean is fixed; the LOS mean
  // follows from the blocked share p at the current elevation: p = T_B / (T_B + T_L).
  blockage_.resize(prns_.size());
  for (std::size_t sat = 0; sat < prns_.size(); ++sat) {
    Xoshiro256ss rng(mix(seed_ ^ kTagBlockage, static_cast<std::uint64_t>(prns_[sat])));
    Blockage& b = blockage_[sat];
    bool blocked = uniform(rng) < blocked_share(spec_, elevation_rad(sat, 0.0));
    b.blocked_at_start = blocked;
    double t = 0.0;
    while (t < end_s) {
      const double p = blocked_share(spec_, elevation_rad(sat, std::min(t, duration_s)));
      double mean_s = spec_.mean_blocked_s;
      if (!blocked) mean_s = p > 0.0 ? spec_.mean_blocked_s * (1.0 - p) / p : std::numeric_limits<double>::infinity();
      const double sojourn_s = mean_s * exponential(rng);
      const double rate_step_end = (std::floor(t / kBlockageRateStep_s) + 1.0) * kBlockageRateStep_s;
      if (t + sojourn_s < rate_step_end) {
        t += sojourn_s;
        b.switch_times_s.push_back(t);
        blocked = !blocked;
      } else {
        t = rate_step_end;
      }
    }
  }

  // Distance the fading pattern is driven through: the antenna's path length, at least the
  // floor speed, integrated by the midpoint rule.
  const auto steps = static_cast<std::size_t>(std::ceil(end_s / kDistanceStep_s)) + 1;
  distance_m_.resize(steps + 1);
  distance_m_[0] = 0.0;
  for (std::size_t i = 0; i < steps; ++i) {
    const double t_mid = (static_cast<double>(i) + 0.5) * kDistanceStep_s;
    const double v = std::max(kFadingSpeedFloor_mps, speed_mps(std::min(t_mid, duration_s)));
    distance_m_[i + 1] = distance_m_[i] + v * kDistanceStep_s;
  }
}

double MultipathChannel::fading_distance_m(double t_s) const {
  const double u = std::max(0.0, t_s) / kDistanceStep_s;
  const auto i = static_cast<std::size_t>(u);
  if (i + 1 >= distance_m_.size()) {
    const std::size_t last = distance_m_.size() - 1;
    const double rate = (distance_m_[last] - distance_m_[last - 1]) / kDistanceStep_s;
    return distance_m_[last] + rate * (t_s - static_cast<double>(last) * kDistanceStep_s);
  }
  const double f = u - static_cast<double>(i);
  return distance_m_[i] + f * (distance_m_[i + 1] - distance_m_[i]);
}

bool MultipathChannel::blocked(std::size_t sat, double t_s) const {
  if (spec_.model != MultipathSpec::Model::land_mobile) return false;
  const Blockage& b = blockage_[sat];
  const auto flips = std::upper_bound(b.switch_times_s.begin(), b.switch_times_s.end(), t_s) - b.switch_times_s.begin();
  return b.blocked_at_start != (flips % 2 == 1);
}

EchoPath MultipathChannel::land_mobile_tap(int prn, int tap, double t_s) const {
  const std::uint64_t key = mix(static_cast<std::uint64_t>(prn), static_cast<std::uint64_t>(tap));
  // Each tap changes reflector every echo_lifetime_s, the taps staggered by a random phase.
  Xoshiro256ss phase_rng(mix(seed_ ^ kTagTapPhase, key));
  const double stagger = uniform(phase_rng);
  const auto generation = static_cast<std::int64_t>(std::floor(t_s / spec_.echo_lifetime_s + stagger));

  Xoshiro256ss rng(mix(mix(seed_ ^ kTagTap, key), static_cast<std::uint64_t>(generation)));
  EchoPath e;
  e.id = static_cast<std::uint32_t>(generation);
  e.excess_delay_m = spec_.mean_excess_delay_m * exponential(rng);
  // Sum of sinusoids over the distance travelled: arrival angle alpha gives a spatial
  // frequency cos(alpha) / lambda, i.e. a Doppler of v cos(alpha) / lambda at speed v.
  const double k_per_m = 2.0 * kPi / gps::kL1Wavelength_m * fading_distance_m(t_s);
  auto ray = [&] {
    const double alpha = 2.0 * kPi * uniform(rng);
    const double phase = 2.0 * kPi * uniform(rng);
    return std::polar(1.0, k_per_m * std::cos(alpha) + phase);
  };
  const std::complex<double> specular = ray();
  std::complex<double> diffuse = 0.0;
  for (int m = 0; m < kFadingSinusoids; ++m) diffuse += ray();
  diffuse /= std::sqrt(static_cast<double>(kFadingSinusoids));
  const double k = spec_.echo_rician_k;
  const double tap_power = std::pow(10.0, spec_.echo_power_db / 10.0) / static_cast<double>(spec_.echoes);
  const std::complex<double> h =
      std::sqrt(tap_power) * (std::sqrt(k / (k + 1.0)) * specular + std::sqrt(1.0 / (k + 1.0)) * diffuse);
  e.amplitude = std::abs(h);
  e.carrier_phase_rad = wrap_pi(std::arg(h));
  return e;
}

PathSet MultipathChannel::paths(std::size_t sat, double t_s, double elevation_rad) const {
  switch (spec_.model) {
    case MultipathSpec::Model::none:
      return PathSet{};
    case MultipathSpec::Model::ground:
      return ground_reflection_paths(spec_, elevation_rad);
    case MultipathSpec::Model::land_mobile:
      break;
  }
  PathSet p;
  if (blocked(sat, t_s)) p.direct_gain = std::pow(10.0, -spec_.blocked_attenuation_db / 20.0);
  p.echo_count = spec_.echoes;
  for (int i = 0; i < spec_.echoes; ++i) p.echoes[static_cast<std::size_t>(i)] = land_mobile_tap(prns_[sat], i, t_s);
  return p;
}

}  // namespace deepnav
