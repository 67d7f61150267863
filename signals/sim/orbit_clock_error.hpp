#pragma once
// Broadcast ephemeris and clock errors: the true satellite is not where the broadcast
// orbit puts it and its clock is not what af0/af1/af2 say. Per satellite, radial,
// along-track and cross-track position errors and a clock error are independent
// first-order Gauss-Markov processes (stationary from the start). Each is drawn once on
// a 60 s grid from its own seeded generator and read back with a C1 cubic (Catmull-Rom)
// interpolation, so it is a smooth, fixed function of time: the synthesizer asks for it
// at every millisecond boundary from parallel chunks in any order.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ins/gps_time.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav {

struct OrbitClockErrorSpec {
  /// RMS (1 sigma) of each component; all 0: the broadcast ephemeris is the truth.
  double radial_m = 0.0;
  double along_m = 0.0;
  double cross_m = 0.0;
  double clock_m = 0.0;  ///< c times the clock error
  double correlation_time_s = 3600.0;

  bool any() const { return radial_m > 0.0 || along_m > 0.0 || cross_m > 0.0 || clock_m > 0.0; }
  /// Global-average signal-in-space range error of the configured sizes for GPS orbits:
  /// sqrt(radial^2 + clock^2 + (along^2 + cross^2) / 49) (radial and clock uncorrelated).
  double global_average_sisre_m() const;
  bool operator==(const OrbitClockErrorSpec&) const = default;
};

/// One satellite's error at one instant.
struct OrbitClockErrorSample {
  Eigen::Vector3d rac_m = Eigen::Vector3d::Zero();  ///< radial, along-track, cross-track
  double clock_m = 0.0;                             ///< c (dts_true - dts_broadcast)
};

class OrbitClockError {
 public:
  /// Draws GPS PRNs 1..32 and Galileo SVIDs 1..50 over [start - 60 s, start + duration + 60 s]
  /// (zero when !spec.any()); each from its own generator, so GPS satellites' errors are
  /// the same with or without Galileo.
  OrbitClockError(const OrbitClockErrorSpec& spec, std::uint64_t seed, const GpsTime& start, double duration_s);

  const OrbitClockErrorSpec& spec() const { return spec_; }
  bool active() const { return spec_.any(); }
  /// The error of satellite `prn` at GPS time t (held at the ends of the span).
  OrbitClockErrorSample at(int prn, const GpsTime& t) const;
  /// The error of satellite `id` (zero for a number outside the drawn ones).
  OrbitClockErrorSample at(const SatelliteId& id, const GpsTime& t) const;

 private:
  static constexpr double kStep_s = 60.0;
  OrbitClockErrorSpec spec_;
  GpsTime grid_start_;
  std::size_t nodes_ = 0;
  /// [GPS prn - 1, then 32 + Galileo SVID - 1][component] -> series on the grid (components:
  /// radial, along, cross, clock).
  std::vector<std::array<std::vector<double>, 4>> series_;
};

/// Rotation from radial/along-track/cross-track axes to ECEF for a satellite at r with
/// inertial velocity v (both ECEF axes): radial = r/|r|, cross = r x v normalised,
/// along = cross x radial.
Eigen::Matrix3d rac_to_ecef(const Eigen::Vector3d& r_ecef_m, const Eigen::Vector3d& v_inertial_ecef_mps);

}  // namespace deepnav
