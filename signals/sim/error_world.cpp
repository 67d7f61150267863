#include "signals/sim/error_world.hpp"

namespace deepnav {

ErrorWorld::ErrorWorld(const ErrorSpec& spec, AtmosphereSwitches switches, std::uint64_t seed, const GpsTime& start,
                       double duration_s, const wgs84::Llh& start_position)
    : spec_(spec),
      switches_(switches),
      ionosphere_(spec.ionosphere, seed, start_position, start),
      troposphere_(spec.troposphere, seed, start, duration_s),
      orbit_clock_(spec.orbit_clock, seed, start, duration_s) {}

ErrorWorld::ErrorWorld(AtmosphereSwitches switches)
    : ErrorWorld(error_preset("none"), switches, 0, GpsTime{}, 0.0, wgs84::Llh{}) {}

}  // namespace deepnav
