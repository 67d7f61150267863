#pragma once
// The troposphere the synthesized signal really crosses. The receiver models it with
// Saastamoinen from a standard atmosphere and the Black & Eisner mapping function; the
// `site` truth differs the way the real atmosphere does: site meteorology, a zenith wet
// delay that wanders (seeded random walk) and the Niell (1996) mapping functions,
// hydrostatic and wet separately. `saastamoinen-standard` keeps the receiver's model as truth.
#include <cstdint>
#include <vector>

#include "ins/gps_time.hpp"

namespace deepnav {

struct TroposphereTruthSpec {
  enum class Model { saastamoinen_standard, site };
  enum class Mapping { niell, black_eisner };
  Model model = Model::saastamoinen_standard;
  /// site: meteorology at mean sea level, carried to the receiver height with the
  /// standard lapse rate (-6.5 K/km) and barometric law; relative humidity is kept.
  double pressure_hpa = 1013.5;
  double temperature_c = 21.0;
  double relative_humidity = 0.75;  ///< 0..1
  /// site: random-walk intensity of the zenith wet delay (bounded at 0 by reflection).
  double wet_random_walk_m_per_sqrt_h = 0.015;
  Mapping mapping = Mapping::niell;  ///< site only

  bool operator==(const TroposphereTruthSpec&) const = default;
};

/// Niell (1996) mapping functions at one elevation.
struct NiellMapping {
  double hydrostatic = 1.0;
  double wet = 1.0;
};

/// Niell mapping functions (Niell 1996, "Global mapping functions for the atmosphere delay
/// at radio wavelengths", JGR 101(B2), tables 3 and 4): continued fractions whose
/// coefficients are interpolated in |latitude| with the annual term (minimum on day 28 in
/// the north, half a year later in the south) plus the hydrostatic height correction.
NiellMapping niell_mapping(double lat_rad, double height_m, double day_of_year, double elevation_rad);

class TroposphereTruth {
 public:
  /// `start` and `duration_s` bound the wet random walk, which is drawn once on a 10 s
  /// grid (so the delay is a fixed function of time, whatever order it is asked in).
  TroposphereTruth(const TroposphereTruthSpec& spec, std::uint64_t seed, const GpsTime& start, double duration_s);

  const TroposphereTruthSpec& spec() const { return spec_; }

  /// Slant delay (m) for a receiver at geodetic latitude (rad) and height (m) looking at
  /// elevation (rad) at GPS time t.
  double delay_m(double lat_rad, double height_m, double elevation_rad, const GpsTime& t) const;
  /// site model: zenith hydrostatic and wet delays (m) at time t (wet includes the walk).
  double zenith_hydrostatic_m(double lat_rad, double height_m) const;
  double zenith_wet_m(double height_m, const GpsTime& t) const;
  /// The random-walk part of the zenith wet delay at t (m).
  double wet_walk_m(const GpsTime& t) const;

 private:
  static constexpr double kWalkStep_s = 10.0;
  TroposphereTruthSpec spec_;
  GpsTime grid_start_;
  double day_of_year_ = 1.0;
  double wet_zenith_sea_level_m_ = 0.0;  ///< from the site meteorology, without the walk
  std::vector<double> wet_sea_level_m_;  ///< with the walk, on the grid from grid_start_
};

}  // namespace deepnav
