#include "signals/sim/troposphere_truth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "signals/atmosphere.hpp"
#include "signals/sim/error_seed.hpp"

namespace deepnav {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kGridMargin_s = 60.0;  // receiver clock bias and drift move true time off the nominal span

using Row = std::array<double, 5>;  // at |latitude| 15, 30, 45, 60, 75 deg

// Niell (1996) table 3 (hydrostatic average and amplitude) and table 4 (wet).
constexpr Row kHydroAvgA{1.2769934e-3, 1.2683230e-3, 1.2465397e-3, 1.2196049e-3, 1.2045996e-3};
constexpr Row kHydroAvgB{2.9153695e-3, 2.9152299e-3, 2.9288445e-3, 2.9022565e-3, 2.9024912e-3};
constexpr Row kHydroAvgC{62.610505e-3, 62.837393e-3, 63.721774e-3, 63.824265e-3, 64.258455e-3};
constexpr Row kHydroAmpA{0.0, 1.2709626e-5, 2.6523662e-5, 3.4000452e-5, 4.1202191e-5};
constexpr Row kHydroAmpB{0.0, 2.1414979e-5, 3.0160779e-5, 7.2562722e-5, 11.723375e-5};
constexpr Row kHydroAmpC{0.0, 9.0128400e-5, 4.3497037e-5, 84.795348e-5, 170.37206e-5};
constexpr Row kWetA{5.8021897e-4, 5.6794847e-4, 5.8118019e-4, 5.9727542e-4, 6.1641693e-4};
constexpr Row kWetB{1.4275268e-3, 1.5138625e-3, 1.4572752e-3, 1.5007428e-3, 1.7599082e-3};
constexpr Row kWetC{4.3472961e-2, 4.6729510e-2, 4.3908931e-2, 4.4626982e-2, 5.4736038e-2};
constexpr double kHeightA = 2.53e-5, kHeightB = 5.49e-3, kHeightC = 1.14e-3;

double interpolate(const Row& row, double abs_lat_deg) {
  if (abs_lat_deg <= 15.0) return row[0];
  if (abs_lat_deg >= 75.0) return row[4];
  const double x = (abs_lat_deg - 15.0) / 15.0;
  const auto i = static_cast<std::size_t>(std::min(3.0, std::floor(x)));
  const double f = x - static_cast<double>(i);
  return row[i] + f * (row[i + 1] - row[i]);
}

/// Marini (1972) continued fraction normalised to 1 at the zenith (Herring's form).
double continued_fraction(double sin_el, double a, double b, double c) {
  return (1.0 + a / (1.0 + b / (1.0 + c))) / (sin_el + a / (sin_el + b / (sin_el + c)));
}

struct Meteorology {
  double pressure_hpa, temperature_k, vapour_hpa;
};

/// Sea-level meteorology carried to height h: -6.5 K/km to 11 km, isothermal above,
/// hydrostatic pressure; the relative humidity is kept (water vapour saturation as in the
/// receiver's model, so the two differ only by their inputs).
Meteorology meteorology_at(const TroposphereTruthSpec& spec, double height_m) {
  constexpr double kLapse_Kpm = 6.5e-3;
  constexpr double kExponent = 5.25588;  // g / (R_d * lapse)
  constexpr double kGOverR_Kpm = 9.80665 / 287.053;
  const double h = std::max(height_m, -500.0);
  const double h_low = std::min(h, 11000.0);
  const double t0_k = spec.temperature_c + 273.15;
  Meteorology m;
  m.temperature_k = t0_k - kLapse_Kpm * h_low;
  m.pressure_hpa = spec.pressure_hpa * std::pow(m.temperature_k / t0_k, kExponent);
  if (h > 11000.0) m.pressure_hpa *= std::exp(-kGOverR_Kpm / m.temperature_k * (h - 11000.0));
  const double t = m.temperature_k;
  m.vapour_hpa = 6.108 * spec.relative_humidity * std::exp((17.15 * t - 4684.0) / (t - 38.45));
  return m;
}

double saastamoinen_wet_m(const Meteorology& m) { return 0.002277 * (1255.0 / m.temperature_k + 0.05) * m.vapour_hpa; }

}  // namespace

NiellMapping niell_mapping(double lat_rad, double height_m, double day_of_year, double elevation_rad) {
  // Below 1 deg the height term's 1/sin(el) grows without bound; signals there are masked anyway.
  const double sin_el = std::sin(std::max(elevation_rad, 1.0 * kDeg));
  const double abs_lat_deg = std::abs(lat_rad) / kDeg;
  const double doy = lat_rad < 0.0 ? day_of_year + 365.25 / 2.0 : day_of_year;
  const double season = std::cos(2.0 * kPi * (doy - 28.0) / 365.25);
  const double a = interpolate(kHydroAvgA, abs_lat_deg) - interpolate(kHydroAmpA, abs_lat_deg) * season;
  const double b = interpolate(kHydroAvgB, abs_lat_deg) - interpolate(kHydroAmpB, abs_lat_deg) * season;
  const double c = interpolate(kHydroAvgC, abs_lat_deg) - interpolate(kHydroAmpC, abs_lat_deg) * season;
  NiellMapping m;
  m.hydrostatic = continued_fraction(sin_el, a, b, c) +
                  (1.0 / sin_el - continued_fraction(sin_el, kHeightA, kHeightB, kHeightC)) * height_m / 1000.0;
  m.wet = continued_fraction(sin_el, interpolate(kWetA, abs_lat_deg), interpolate(kWetB, abs_lat_deg),
                             interpolate(kWetC, abs_lat_deg));
  return m;
}

TroposphereTruth::TroposphereTruth(const TroposphereTruthSpec& spec, std::uint64_t seed, const GpsTime& start,
                                   double duration_s)
    : spec_(spec), grid_start_(start.plus_seconds(-kGridMargin_s)) {
  CalendarTime jan1 = calendar_from_gps_time(start);
  jan1.month = jan1.day = 1;
  jan1.hour = jan1.minute = 0;
  jan1.second = 0.0;
  day_of_year_ = 1.0 + start.seconds_since(gps_time_from_calendar(jan1)) / 86400.0;
  if (spec_.model != TroposphereTruthSpec::Model::site) return;

  wet_zenith_sea_level_m_ = saastamoinen_wet_m(meteorology_at(spec_, 0.0));
  // The walk moves the sea-level zenith wet delay and is reflected at 0 (the delay cannot
  // go negative); other heights scale it with the wet delay's height profile. It starts
  // at the run's start and is drawn forward to the end, then backward over the margin.
  const auto nodes = static_cast<std::size_t>(std::ceil((duration_s + 2.0 * kGridMargin_s) / kWalkStep_s)) + 1;
  const auto start_node = static_cast<std::size_t>(kGridMargin_s / kWalkStep_s);
  wet_sea_level_m_.assign(nodes, wet_zenith_sea_level_m_);
  // Forward and backward have their own generators: a longer run repeats a shorter one.
  auto forward = error_rng(seed, ErrorSource::troposphere, 0, 0);
  auto backward = error_rng(seed, ErrorSource::troposphere, 0, 1);
  std::normal_distribution<double> normal_forward(0.0, 1.0), normal_backward(0.0, 1.0);
  const double step_sigma_m = spec_.wet_random_walk_m_per_sqrt_h * std::sqrt(kWalkStep_s / 3600.0);
  for (std::size_t i = start_node + 1; i < nodes; ++i)
    wet_sea_level_m_[i] = std::abs(wet_sea_level_m_[i - 1] + step_sigma_m * normal_forward(forward));
  for (std::size_t i = start_node; i-- > 0;)
    wet_sea_level_m_[i] = std::abs(wet_sea_level_m_[i + 1] + step_sigma_m * normal_backward(backward));
}

double TroposphereTruth::wet_walk_m(const GpsTime& t) const {
  const std::vector<double>& w = wet_sea_level_m_;
  if (w.size() < 2) return 0.0;
  const double x = std::clamp(t.seconds_since(grid_start_) / kWalkStep_s, 0.0, static_cast<double>(w.size() - 1));
  const auto i = std::min(static_cast<std::size_t>(x), w.size() - 2);
  const double f = x - static_cast<double>(i);
  return w[i] + f * (w[i + 1] - w[i]) - wet_zenith_sea_level_m_;
}

double TroposphereTruth::zenith_hydrostatic_m(double lat_rad, double height_m) const {
  const Meteorology m = meteorology_at(spec_, height_m);
  const double h = std::max(height_m, -500.0);
  return 0.0022768 * m.pressure_hpa / (1.0 - 0.00266 * std::cos(2.0 * lat_rad) - 0.00028 * h / 1000.0);
}

double TroposphereTruth::zenith_wet_m(double height_m, const GpsTime& t) const {
  const double wet_m = saastamoinen_wet_m(meteorology_at(spec_, height_m));
  if (!(wet_zenith_sea_level_m_ > 0.0)) return wet_m + wet_walk_m(t);  // dry air: the walk alone
  return wet_m * (1.0 + wet_walk_m(t) / wet_zenith_sea_level_m_);
}

double TroposphereTruth::delay_m(double lat_rad, double height_m, double elevation_rad, const GpsTime& t) const {
  if (spec_.model == TroposphereTruthSpec::Model::saastamoinen_standard)
    return troposphere_delay_m(lat_rad, height_m, elevation_rad);
  const double hydro_m = zenith_hydrostatic_m(lat_rad, height_m);
  const double wet_m = zenith_wet_m(height_m, t);
  if (spec_.mapping == TroposphereTruthSpec::Mapping::black_eisner)
    return (hydro_m + wet_m) * troposphere_mapping(elevation_rad);
  const NiellMapping m = niell_mapping(lat_rad, height_m, day_of_year_, elevation_rad);
  return hydro_m * m.hydrostatic + wet_m * m.wet;
}

}  // namespace deepnav
