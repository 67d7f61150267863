#pragma once
// Which atmosphere models the receiver applies to its ranges: the one choice that the
// PVT solution, the tight filter's predicted ranges and the ultra-tight NCO commands all
// read, so that they never disagree on the delays.
//
// The defaults (Klobuchar with the broadcast or assisted parameters, Saastamoinen with a
// standard atmosphere) suit live signals. Turning a model off suits IF data from a
// generator that leaves that delay out (gps-sdr-sim has no troposphere): applying a delay
// that is not in the signal biases the solution, mostly its height (a zenith
// troposphere of 2.4 m becomes several metres of height error).
#include <string>
#include <vector>

#include "signals/iono_utc.hpp"

namespace deepnav {

enum class IonosphereModel {
  none,       ///< no ionosphere correction, even when broadcast alpha/beta are decoded or assisted
  klobuchar,  ///< broadcast Klobuchar model (IS-GPS-200 20.3.3.5.2.5) when its parameters are known
};

enum class TroposphereModel {
  none,          ///< no troposphere correction
  saastamoinen,  ///< Saastamoinen zenith delays, standard atmosphere, Black & Eisner mapping
};

/// "none", "klobuchar"; throws std::invalid_argument listing them otherwise.
IonosphereModel parse_ionosphere_model(const std::string& name);
/// "none", "saastamoinen"; throws std::invalid_argument listing them otherwise.
TroposphereModel parse_troposphere_model(const std::string& name);
std::string to_string(IonosphereModel model);
std::string to_string(TroposphereModel model);
/// Every accepted name, in the order of the enumerators.
std::vector<std::string> ionosphere_model_names();
std::vector<std::string> troposphere_model_names();

struct AtmosphereModels {
  IonosphereModel ionosphere = IonosphereModel::klobuchar;
  TroposphereModel troposphere = TroposphereModel::saastamoinen;

  /// L1 C/A code group delay of the ionosphere (m) for a receiver at geodetic latitude and
  /// longitude, a satellite at azimuth/elevation (radians) and GPS time of week `t_sow`:
  /// 0 with the model off or without valid parameters (none decoded or assisted yet).
  double ionosphere_delay_m(const IonoParameters& iono, double lat_rad, double lon_rad, double azimuth_rad,
                            double elevation_rad, double t_sow) const;
  /// Slant troposphere delay (m) at the receiver's latitude and height for a satellite at
  /// `elevation_rad`: 0 with the model off.
  double troposphere_delay_m(double lat_rad, double height_m, double elevation_rad) const;
};

}  // namespace deepnav
