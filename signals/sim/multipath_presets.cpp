#include "signals/sim/multipath_presets.hpp"

#include <stdexcept>

namespace deepnav {

MultipathSpec multipath_for_environment(std::string_view environment) {
  MultipathSpec m;
  if (environment == "none") return m;
  if (environment == "open-sky") {
    m.model = MultipathSpec::Model::ground;
    m.antenna_height_m = 1.5;
    m.reflection_coefficient = 0.3;
    m.below_horizon_gain_db = -20.0;
    return m;
  }
  if (environment == "suburban") {
    m.model = MultipathSpec::Model::land_mobile;
    m.echoes = 3;
    m.echo_power_db = -12.0;
    m.echo_rician_k = 0.0;
    m.mean_excess_delay_m = 20.0;
    m.echo_lifetime_s = 5.0;
    m.blocked_probability = 0.10;
    m.mean_blocked_s = 1.5;
    m.blocked_attenuation_db = 15.0;
    return m;
  }
  if (environment == "urban") {
    m.model = MultipathSpec::Model::land_mobile;
    m.echoes = 5;
    m.echo_power_db = -6.0;
    m.echo_rician_k = 0.0;
    m.mean_excess_delay_m = 50.0;
    m.echo_lifetime_s = 3.0;
    m.blocked_probability = 0.35;
    m.mean_blocked_s = 3.0;
    m.blocked_attenuation_db = 25.0;
    return m;
  }
  throw std::invalid_argument("unknown environment '" + std::string(environment) +
                              "' (expected none, open-sky, suburban or urban)");
}

std::vector<std::string> multipath_environments() { return {"none", "open-sky", "suburban", "urban"}; }

}  // namespace deepnav
