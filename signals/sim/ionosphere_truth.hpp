#pragma once
// The ionosphere the synthesized signal really crosses. The receiver removes the
// broadcast Klobuchar model; to leave it a realistic residual the truth here is a
// different model: a thin-shell vertical TEC field with its own diurnal shape,
// geomagnetic-latitude profile and seeded travelling disturbances, mapped to the
// slant with the standard single-layer mapping function (not Klobuchar's slant
// factor). `klobuchar` keeps the broadcast model as truth (optionally scaled).
#include <cstdint>
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {

struct IonosphereTruthSpec {
  enum class Model { klobuchar, thin_shell };
  Model model = Model::klobuchar;
  /// Multiplies the truth delay of either model (1: the model as it is).
  double vtec_scale = 1.0;
  /// thin_shell: vertical TEC at 14 h local solar time on the crest of the equatorial
  /// anomaly (geomagnetic latitude 15 deg); the latitude profile scales it elsewhere.
  double day_vtec_tecu = 50.0;
  /// thin_shell: the night floor at the same latitude (reached at 05 h local time).
  double night_vtec_tecu = 4.0;
  double shell_height_m = 450e3;
  /// thin_shell: RMS of the relative VTEC modulation by travelling ionospheric
  /// disturbances (three seeded plane waves, 150-400 km wavelength, 15-60 min period).
  double disturbance_rms = 0.03;

  bool operator==(const IonosphereTruthSpec&) const = default;
};

/// Vertical TEC at the pierce point and the slant L1 delay of one line of sight.
struct IonosphereSample {
  double vtec_tecu = 0.0;
  double mapping = 1.0;  ///< slant / vertical
  double delay_m = 0.0;  ///< L1 code group delay (the carrier advances by as much)
};

class IonosphereTruth {
 public:
  /// `seed` draws the disturbances; `reference` and `reference_time` are the receiver's
  /// start (the disturbance phases are counted from there).
  IonosphereTruth(const IonosphereTruthSpec& spec, std::uint64_t seed, const wgs84::Llh& reference,
                  const GpsTime& reference_time);

  const IonosphereTruthSpec& spec() const { return spec_; }

  /// L1 group delay (m) for a receiver at `rx` looking at azimuth/elevation (rad) at GPS
  /// time t. `klobuchar_m` is the broadcast model's delay for the same look (the truth of
  /// the klobuchar model; 0 when the navigation data has no ionosphere parameters).
  double delay_m(double klobuchar_m, const wgs84::Llh& rx, double azimuth_rad, double elevation_rad,
                 const GpsTime& t) const;
  /// The thin-shell model in detail (whatever spec().model says).
  IonosphereSample thin_shell(const wgs84::Llh& rx, double azimuth_rad, double elevation_rad, const GpsTime& t) const;

 private:
  struct Wave {
    double k_east_radpm = 0.0, k_north_radpm = 0.0;  ///< wave vector
    double omega_radps = 0.0;
    double phase_rad = 0.0;
    double amplitude = 0.0;  ///< relative VTEC modulation
  };
  IonosphereTruthSpec spec_;
  wgs84::Llh reference_;
  GpsTime reference_time_;
  std::vector<Wave> waves_;
};

/// The standard single-layer (thin shell) mapping function at shell height H:
/// M(E) = 1 / sqrt(1 - (R cos E / (R + H))^2), R the mean Earth radius.
double single_layer_mapping(double elevation_rad, double shell_height_m);

/// L1 group delay (m) of a slant TEC in TEC units: 40.3 * STEC / f_L1^2.
double l1_delay_m_from_tecu(double slant_tecu);

}  // namespace deepnav
