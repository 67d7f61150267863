#pragma once
// The scenario's multipath and blockage settings (`multipath:` in the scenario YAML):
// which channel model puts echoes and shadowing into the samples, and its parameters.
// The models themselves are in multipath_channel.hpp; named environments in
// multipath_presets.hpp.
#include <stdexcept>
#include <string>
#include <string_view>

namespace deepnav {

struct MultipathSpec {
  /// none: the direct line-of-sight signal only (the synthesizer does no extra work).
  /// ground: one specular reflection off flat ground below a static or slow antenna.
  /// land_mobile: a two-state (LOS/blocked) shadowing process per satellite plus
  /// fading echoes with random excess delays, for vehicles.
  enum class Model { none, ground, land_mobile };
  Model model = Model::none;

  // --- ground ---
  double antenna_height_m = 1.5;        ///< antenna phase centre above the reflecting plane
  double reflection_coefficient = 0.5;  ///< |Gamma|, amplitude (0.3 dry soil .. 0.6 wet soil, ~0.8 water)
  /// Antenna gain towards the reflected arrival (from below the horizon) relative to the
  /// gain towards the direct one; the rejection fades in over the first 10 degrees of
  /// elevation because an antenna cannot tell +1 degree from -1 degree.
  double below_horizon_gain_db = -15.0;

  // --- land-mobile ---
  int echoes = 3;                     ///< fading echo taps per satellite (0..kMaxEchoes)
  double echo_power_db = -10.0;       ///< mean power of all echoes together relative to the unblocked direct signal
  double echo_rician_k = 0.0;         ///< Rician K (linear) of each echo tap; 0 = Rayleigh
  double mean_excess_delay_m = 30.0;  ///< mean of the exponentially distributed tap delays
  double echo_lifetime_s = 5.0;       ///< a tap keeps its delay this long, then a new reflector takes over
  /// Long-run fraction of time a satellite at 30 degrees elevation is blocked; it scales as
  /// 2 (1 - sin(elevation)) (twice that at the horizon, never at the zenith), capped at 0.95.
  double blocked_probability = 0.1;
  double mean_blocked_s = 2.0;           ///< mean duration of a blocked period (exponential)
  double blocked_attenuation_db = 20.0;  ///< direct-path attenuation while blocked (echoes stay)

  static constexpr int kMaxEchoes = 8;
  bool operator==(const MultipathSpec&) const = default;
};

inline std::string_view to_string(MultipathSpec::Model model) {
  switch (model) {
    case MultipathSpec::Model::none:
      return "none";
    case MultipathSpec::Model::ground:
      return "ground";
    case MultipathSpec::Model::land_mobile:
      return "land-mobile";
  }
  return "none";
}

/// "none" | "ground" | "land-mobile"; throws std::invalid_argument naming the choices.
inline MultipathSpec::Model parse_multipath_model(std::string_view text) {
  if (text == "none") return MultipathSpec::Model::none;
  if (text == "ground") return MultipathSpec::Model::ground;
  if (text == "land-mobile") return MultipathSpec::Model::land_mobile;
  throw std::invalid_argument("expected none, ground or land-mobile, got '" + std::string(text) + "'");
}

}  // namespace deepnav
