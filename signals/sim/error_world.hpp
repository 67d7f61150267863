#pragma once
// Everything about a satellite's signal that the receiver's models get wrong, built once
// per run from the scenario and read (const) at every millisecond boundary: the true
// ionosphere and troposphere, the broadcast orbit and clock errors and the receiver
// antenna's gain pattern. Each model is a fixed function of time, so boundaries may be
// evaluated in any order from any thread.
#include <cstdint>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "signals/sim/error_presets.hpp"

namespace deepnav {

/// The scenario's `ionosphere: false` / `troposphere: false` switches: they take the delay
/// out of the signal altogether (mismatch experiments), whatever the error world says.
struct AtmosphereSwitches {
  bool ionosphere = true;
  bool troposphere = true;
};

class ErrorWorld {
 public:
  /// `start` is the scenario start, `duration_s` its length, `start_position` where the
  /// receiver begins; `seed` the scenario seed (each source derives its own generators).
  ErrorWorld(const ErrorSpec& spec, AtmosphereSwitches switches, std::uint64_t seed, const GpsTime& start,
             double duration_s, const wgs84::Llh& start_position);
  /// The broadcast models as truth (preset none) with the given switches.
  explicit ErrorWorld(AtmosphereSwitches switches);

  const ErrorSpec& spec() const { return spec_; }
  AtmosphereSwitches switches() const { return switches_; }
  const IonosphereTruth& ionosphere() const { return ionosphere_; }
  const TroposphereTruth& troposphere() const { return troposphere_; }
  const OrbitClockError& orbit_clock() const { return orbit_clock_; }
  const AntennaSpec& antenna() const { return spec_.antenna; }

 private:
  ErrorSpec spec_;
  AtmosphereSwitches switches_;
  IonosphereTruth ionosphere_;
  TroposphereTruth troposphere_;
  OrbitClockError orbit_clock_;
};

}  // namespace deepnav
