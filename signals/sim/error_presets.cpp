#include "signals/sim/error_presets.hpp"

#include "signals/sim/multipath_presets.hpp"

#include <stdexcept>

namespace deepnav {
namespace {

/// The error world of a real receiver under an open sky, mid-latitude, moderate solar activity.
ErrorSpec open_sky() {
  ErrorSpec e;
  e.preset = "open-sky";
  // Ionosphere: Klobuchar removes about half of the real delay (Klobuchar 1987, IEEE Trans.
  // AES-23(3): the model was designed to correct at least 50 % RMS). Vertical TEC of 5-50 TECU covers quiet to
  // moderately active days at mid-latitudes (e.g. the IGS global ionosphere maps); here 50
  // TECU at the 14 h peak on the anomaly crest (45 at Seoul, 32 at Munich) and 4 TECU at
  // night (3-4). Against the bundled January 2022 broadcast parameters (Klobuchar: 28 TECU
  // by day, 9 at night) the residual after Klobuchar is 45 % of the delay over a day at
  // Seoul and 30-40 % at other mid-latitude sites (tests/signals/ionosphere_truth_test.cpp).
  // Travelling disturbances of 3 % RMS (Hernandez-Pajares et al. 2006, Radio Science 41:
  // MSTIDs of 0.1-1 TECU, i.e. a few percent of the daytime TEC). Thin shell at 450 km, the
  // single-layer height of the IGS ionosphere maps (IONEX), where Klobuchar uses 350 km.
  e.ionosphere.model = IonosphereTruthSpec::Model::thin_shell;
  e.ionosphere.vtec_scale = 1.0;
  e.ionosphere.day_vtec_tecu = 50.0;
  e.ionosphere.night_vtec_tecu = 4.0;
  e.ionosphere.shell_height_m = 450e3;
  e.ionosphere.disturbance_rms = 0.03;
  // Troposphere: the mid-latitude (45 deg) summer meteorology of the UNB3 model (Collins &
  // Langley 1997, from the US Standard Atmosphere supplements): 1013.5 hPa, 294.15 K and
  // 18.9 hPa water vapour (75 % relative humidity), against the receiver's 1013.25 hPa,
  // 288.15 K and 70 %: about 7 cm more zenith wet delay. The zenith wet delay wanders by
  // 1.5 cm/sqrt(h), inside the 1-2 cm/sqrt(h) random walk usual for it in GPS geodesy and
  // PPP filters (cf. Tralli & Lichten 1990, Bulletin Geodesique 64). Niell (1996) mapping
  // functions instead of the receiver's Black & Eisner.
  e.troposphere.model = TroposphereTruthSpec::Model::site;
  e.troposphere.pressure_hpa = 1013.5;
  e.troposphere.temperature_c = 21.0;
  e.troposphere.relative_humidity = 0.75;
  e.troposphere.wet_random_walk_m_per_sqrt_h = 0.015;
  e.troposphere.mapping = TroposphereTruthSpec::Mapping::niell;
  // Broadcast orbit and clock: GPS broadcast ephemeris errors against precise products are
  // about 0.2-0.4 m radial, 1 m along-track, 0.5 m cross-track and 0.5 m clock RMS
  // (Montenbruck, Steigenberger & Hauschild 2015, "Broadcast versus precise ephemerides: a
  // multi-GNSS perspective", GPS Solutions 19; Heng et al. 2011): global-average SISRE
  // sqrt(0.3^2 + 0.5^2 + (1^2 + 0.5^2)/49) = 0.60 m. Correlation time 1 h (the errors change
  // over hours, between uploads and along the orbit).
  e.orbit_clock.radial_m = 0.3;
  e.orbit_clock.along_m = 1.0;
  e.orbit_clock.cross_m = 0.5;
  e.orbit_clock.clock_m = 0.5;
  e.orbit_clock.correlation_time_s = 3600.0;
  // Antenna: a typical L1 patch (0 dB at the zenith, about -5 dB at 10 deg, -10 dB at the horizon).
  e.antenna.pattern = AntennaSpec::Pattern::patch;
  e.antenna.gain_10deg_db = -5.0;
  e.antenna.gain_horizon_db = -10.0;
  return e;
}

}  // namespace

const std::vector<std::string>& error_preset_names() {
  static const std::vector<std::string> names{"none", "open-sky", "suburban", "urban"};
  return names;
}

ErrorSpec error_preset(const std::string& name) {
  // none: the receiver's own models are the truth (today's synthesizer): broadcast
  // Klobuchar, standard-atmosphere Saastamoinen with Black & Eisner, broadcast orbit and
  // clock, isotropic antenna. The other fields keep open-sky's values so that switching a
  // single model on gives realistic sizes.
  if (name == "none") {
    ErrorSpec e = open_sky();
    e.preset = "none";
    e.ionosphere.model = IonosphereTruthSpec::Model::klobuchar;
    e.troposphere.model = TroposphereTruthSpec::Model::saastamoinen_standard;
    e.orbit_clock = OrbitClockErrorSpec{};
    e.antenna.pattern = AntennaSpec::Pattern::isotropic;
    return e;
  }
  // The atmosphere, the broadcast errors and the antenna do not depend on the surroundings:
  // suburban and urban share open-sky's values; their multipath and blockage differ
  // (multipath_presets.cpp: a weak ground reflection in open sky, a land-mobile channel
  // with more blockage and stronger echoes towards the city).
  if (name == "open-sky" || name == "suburban" || name == "urban") {
    ErrorSpec e = open_sky();
    e.preset = name;
    e.multipath = multipath_for_environment(name);
    return e;
  }
  std::string list;
  for (const auto& n : error_preset_names()) list += (list.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown error preset '" + name + "' (expected one of: " + list + ")");
}

}  // namespace deepnav
