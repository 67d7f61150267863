#pragma once
// The date this program was built: the last resort for resolving the 10-bit GPS week a
// satellite broadcasts, when neither the user nor an assistance file says when the data are
// from (any data within 512 weeks, about ten years, of the build resolve right).
#include "ins/gps_time.hpp"

namespace deepnav {

/// Midday of the build date (the compiler's __DATE__) on the GPS time scale.
GpsTime build_time();

}  // namespace deepnav
