#pragma once
// The error world of a scenario: how the truth the synthesizer uses differs from the
// broadcast models the receiver removes (ionosphere, troposphere, orbit and clock) and the
// receiver antenna's gain pattern, and the multipath and blockage around it. A preset fills every field; explicit scenario fields
// override it. Values and their sources: error_presets.cpp.
#include <string>
#include <vector>

#include "signals/sim/antenna_pattern.hpp"
#include "signals/sim/ionosphere_truth.hpp"
#include "signals/sim/multipath_spec.hpp"
#include "signals/sim/orbit_clock_error.hpp"
#include "signals/sim/troposphere_truth.hpp"

namespace deepnav {

struct ErrorSpec {
  std::string preset = "none";
  IonosphereTruthSpec ionosphere{};
  TroposphereTruthSpec troposphere{};
  OrbitClockErrorSpec orbit_clock{};
  AntennaSpec antenna{};
  MultipathSpec multipath{};  ///< echoes and blockage (none: the direct signal only)

  bool operator==(const ErrorSpec&) const = default;
};

/// none | open-sky | suburban | urban. Throws std::invalid_argument naming the presets.
ErrorSpec error_preset(const std::string& name);
const std::vector<std::string>& error_preset_names();

}  // namespace deepnav
