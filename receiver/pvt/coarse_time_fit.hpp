#pragma once
// One coarse-time fix from sub-millisecond pseudoranges (van Diggelen, "A-GPS: Assisted
// GPS, GNSS and SBAS", ch. 4): the whole milliseconds of each pseudorange taken from a
// predicted range, then a five-unknown weighted least squares.
//
// Whole milliseconds. From a start position and time every satellite's pseudorange is
// predicted (less the receiver clock). The reference satellite (the highest: its range
// moves least with a horizontal position error and its range rate is smallest) gets the
// whole milliseconds that put the common offset within +-0.5 ms; every other satellite
// gets those that bring its pseudorange, with that offset, nearest its prediction. This
// is right while each satellite's predicted range, relative to the reference's, is off by
// less than half a code period (c * 0.5 ms = 150 km):
//   |(u_k - u_ref) . dx + (v_k - v_ref) dt| < 150 km
// with dx the start's position error, dt its time error, u the lines of sight and v the
// range rates (at most ~800 m/s, so a minute of time error uses up to ~50-100 km of it).
//
// Five unknowns. The pseudorange of satellite k at true receive time t_hint + t_c is
//   P_k = |r_k(t_hint + t_c - tau_k) - x| + b - c dts_k + I_k + T_k
// (orbit at the transmit time, Earth rotation during the flight, satellite clock with
// relativity and TGD, the receiver's atmosphere models: receiver/pvt/range_model.hpp, the
// same as the PVT and the aided modes). Linearised in x, b and t_c its row is
//   [-u_k', 1, rate_k]
// where rate_k is the satellite's pseudorange rate seen from the (static) receiver: a
// time error moves every satellite along its own range rate, which is what separates
// t_c from the clock bias b. Gauss-Newton, weights 1 / sigma^2 with sigma^2 the
// RangeErrorModel's elevation terms plus the code phase's own noise.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/pvt/atmosphere_models.hpp"
#include "receiver/pvt/range_weight.hpp"
#include "signals/ephemeris.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav {

/// One satellite of a snapshot, ready for the fit.
struct CoarseTimeSatellite {
  int prn = 0;
  const Ephemeris* ephemeris = nullptr;
  double submillisecond_m = 0.0;  ///< c (t_hint - t_sv) modulo c * 1 ms (snapshot_measurement.hpp)
  double code_sigma_m = 0.0;      ///< noise of the code phase itself (1 sigma)
};

/// What every fit of one snapshot shares.
struct CoarseTimeContext {
  GpsTime t_hint{};  ///< approximate GPS time of the receive sample
  IonoParameters iono;
  AtmosphereModels atmosphere;
  RangeErrorModel range_errors;
};

struct CoarseTimeState {
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  double clock_bias_m = 0.0;       ///< b: c (t_hint - t_receive) modulo c * 1 ms, plus the fit's whole ms
  double time_correction_s = 0.0;  ///< t_c: true receive time minus t_hint
};

/// The full pseudoranges of a fit: whole milliseconds and the start's common offset.
struct WholeMilliseconds {
  std::vector<int> milliseconds;  ///< per satellite, in the satellites' order
  std::size_t reference = 0;      ///< index of the reference satellite
  double clock_bias_m = 0.0;      ///< the common offset that puts the reference on its prediction
};

/// Whole milliseconds from the sub-millisecond pseudoranges `submillisecond_m` and the
/// predicted pseudoranges less the receiver clock `predicted_m` (same order), relative to
/// satellite `reference`.
WholeMilliseconds resolve_whole_milliseconds(const std::vector<double>& submillisecond_m,
                                             const std::vector<double>& predicted_m, std::size_t reference);

/// The same from the satellites' ranges predicted at `start` (position and time
/// correction), with the highest satellite there as the reference.
WholeMilliseconds resolve_whole_milliseconds(const std::vector<CoarseTimeSatellite>& satellites,
                                             const CoarseTimeContext& context, const CoarseTimeState& start);

/// One least-squares fix and what its residual test needs: rows in the satellites' order.
struct CoarseTimeFit {
  bool converged = false;
  std::string reason;  ///< why not converged
  CoarseTimeState state;
  int iterations = 0;
  Eigen::MatrixXd H;                  ///< n x 5: line of sight, clock, range rate (last iteration)
  Eigen::VectorXd w;                  ///< weights 1 / sigma^2 (1/m^2)
  Eigen::VectorXd residuals_m;        ///< post-fit
  std::vector<double> pseudorange_m;  ///< the full pseudoranges fitted
  std::vector<double> elevation_rad;  ///< at the fix
};

/// Gauss-Newton from `start` (its clock bias is replaced by `ms.clock_bias_m`) with the
/// pseudoranges that `ms` makes whole; at most `max_iterations`.
CoarseTimeFit fit_coarse_time(const std::vector<CoarseTimeSatellite>& satellites, const WholeMilliseconds& ms,
                              const CoarseTimeContext& context, const CoarseTimeState& start, int max_iterations);

}  // namespace deepnav
