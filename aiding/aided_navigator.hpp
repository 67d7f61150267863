#pragma once
// The strapdown INS with its 17-state error filter, closed loop: after every measurement
// update the estimated position, velocity and attitude errors are taken out of the INS
// and the bias estimates added to its bias compensation, then those states return to
// zero. The antenna is where GNSS measures; the INS computes the IMU's position, so every
// measurement goes through the lever arm (IMU -> antenna, body axes).
//
// Measurements (each z = predicted - measured = H dx + v; their rows and noise models are
// in measurement_models.hpp):
//   loose:  antenna position (NED metres) and velocity from a GNSS PVT solution;
//   ranges: per satellite, a pseudorange and/or a pseudorange rate (tight coupling, and
//           the ultra-tight receiver's discriminator-corrected ranges and rates).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "aiding/error_state.hpp"
#include "aiding/ins_error_model.hpp"
#include "aiding/satellite_fault_monitor.hpp"
#include "ins/kalman_filter.hpp"
#include "ins/strapdown.hpp"
#include "receiver/pvt/range_model.hpp"

namespace deepnav::aiding {

/// 1-sigma uncertainty of the starting state (P0 is diagonal).
struct InitialUncertainty {
  Eigen::Vector3d position_ned_m{5.0, 5.0, 10.0};
  Eigen::Vector3d velocity_ned_mps{0.5, 0.5, 0.5};
  Eigen::Vector3d attitude_rad{0.03 * M_PI / 180, 0.03 * M_PI / 180, 5.0 * M_PI / 180};
  Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Constant(500e-6 * 9.80665);
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Constant(3.0 * M_PI / 180 / 3600);
  double clock_bias_m = 10.0;
  double clock_drift_mps = 1.0;
  /// Zenith troposphere residual: what a standard atmosphere misses (weather, a site far
  /// from it) is a few centimetres to decimetres; without a receiver model, the whole delay.
  double troposphere_zenith_m = 0.5;
  /// Scale error of the ionosphere model: Klobuchar removes about half of the delay in
  /// practice, so its scale is uncertain by about that much.
  double ionosphere_scale = 0.5;
};

/// The zenith troposphere residual state (error_state.hpp): a common delay, mapped to each
/// satellite by the receiver's mapping function, that the pseudoranges share. Without it a
/// filter that integrates pseudoranges for minutes takes the residual as white noise and
/// turns its elevation-dependent pattern into a height and clock error (a few metres when
/// the signal has no troposphere and the receiver removes a model).
struct TroposphereResidualConfig {
  bool enabled = false;
  /// Take the state when the pseudorange residuals show the troposphere model over the
  /// signal at the zenith (delay_mismatch_detector.hpp).
  bool enable_on_mismatch = true;
  double random_walk_m_per_sqrt_h = 0.02;  ///< wet delay wander (1-3 cm/sqrt(h) in the literature)
};

/// The ionosphere scale state (error_state.hpp): the signal's ionospheric delay is (1 + s)
/// times the receiver model's, s common to the satellites. The delay is mapped to each
/// satellite by the model itself, and the carrier sees it advanced at the model's rate with
/// the opposite sign; a Doppler row predicted with the model's rate the signal does not
/// have would otherwise be turned into velocity and, integrated, into height.
struct IonosphereResidualConfig {
  bool enabled = false;
  /// Take the state when the pseudorange residuals show the model's delay missing from
  /// the signal (delay_mismatch_detector.hpp).
  bool enable_on_mismatch = true;
  double random_walk_per_sqrt_h = 0.1;  ///< the model's error changes over hours (the TEC's day)
};

struct NavigatorConfig {
  ProcessNoise noise;
  Eigen::Vector3d lever_arm_imu_to_antenna_b_m = Eigen::Vector3d::Zero();
  double gate_sigma = 5.0;  ///< innovation gate of the GNSS updates (0: none)
  TroposphereResidualConfig troposphere;
  IonosphereResidualConfig ionosphere;
};

/// A satellite's measurement for a range update; either part may be absent.
struct RangeMeasurement {
  SatelliteId satellite;
  RangePrediction geometry;  ///< satellite geometry at the antenna estimate
  std::optional<double> pseudorange_m;
  double pseudorange_sigma_m = 5.0;
  std::optional<double> rate_mps;  ///< pseudorange rate (= -lambda * Doppler)
  double rate_sigma_mps = 0.1;
  /// Measurement time minus the navigator's time (the geometry must already be for the
  /// measurement time); the clock model is moved by it.
  double time_offset_s = 0.0;
  /// A rate measured at another time than the pseudorange (a Doppler averaged over a
  /// window refers to its middle): the geometry for that time and its offset from the
  /// navigator's time; the predicted rate takes the antenna velocity there.
  bool rate_at_own_time = false;
  RangePrediction rate_geometry;
  double rate_time_offset_s = 0.0;
};

class AidedNavigator {
 public:
  AidedNavigator(const NavState& initial, double clock_bias_m, double clock_drift_mps, const NavigatorConfig& config,
                 const InitialUncertainty& uncertainty);

  /// Strapdown update with one IMU sample, then the covariance over the same interval.
  void propagate(const ImuSample& sample);

  /// A PVT fix: position at time_s() + time_offset_s, velocity at time_s() +
  /// velocity_time_offset_s (a Doppler velocity is a mean over the Dopplers' window, earlier
  /// than the fix; the INS velocity there is compared with it).
  KalmanUpdate update_position_velocity(const Eigen::Vector3d& r_antenna_ecef_m,
                                        const Eigen::Vector3d& v_antenna_ecef_mps,
                                        const Eigen::Vector3d& position_sigma_ned_m,
                                        const Eigen::Vector3d& velocity_sigma_ned_mps, double time_offset_s = 0.0,
                                        std::optional<double> velocity_time_offset_s = std::nullopt);
  /// Range rows of several satellites in one update. With `innovations`, each satellite's
  /// pseudorange row reports its normalised innovation against the prior (and whether the
  /// gate turned it away) for the per-satellite fault monitor; `test_only` measurements are
  /// reported there but not used (excluded satellites, still watched).
  KalmanUpdate update_ranges(const std::vector<RangeMeasurement>& measurements,
                             std::vector<SatelliteInnovation>* innovations = nullptr,
                             const std::vector<RangeMeasurement>& test_only = {});

  /// What the filter predicts (its prior) for a measurement's pseudorange and for its rate,
  /// each at the measurement's time: the rows of update_ranges are these minus the measured.
  double predicted_pseudorange_m(const RangeMeasurement& m) const;
  double predicted_rate_mps(const RangeMeasurement& m) const;

  /// Zero-velocity update: the IMU is at rest (a stationarity detector says so), its NED
  /// velocity is zero to within sigma_mps on each axis.
  KalmanUpdate update_zero_velocity(double sigma_mps);

  /// Adds a known step to the receiver clock bias (the receiver re-set its clock).
  void shift_clock_bias(double step_m) { clock_bias_m_ += step_m; }

  const NavState& ins() const { return ins_.state(); }
  double time_s() const { return ins_.state().t_s; }
  Eigen::Vector3d antenna_ecef_m() const;
  Eigen::Vector3d antenna_velocity_ecef_mps() const;
  wgs84::Llh antenna_llh() const;
  double clock_bias_m() const { return clock_bias_m_; }
  double clock_drift_mps() const { return clock_drift_mps_; }
  /// Starts estimating the zenith troposphere residual from now on, from `zenith_m` (the
  /// fixes' fit) with this 1-sigma (m); the position and clock variances grow to match.
  /// Returns the 1-sigma room given to the height (m).
  double enable_troposphere_state(double zenith_m, double sigma_m);
  bool troposphere_state_enabled() const { return cfg_.troposphere.enabled; }
  /// The estimated zenith troposphere residual (m; 0 while the state is off).
  double troposphere_residual_m() const { return troposphere_residual_m_; }
  /// Starts estimating the ionosphere model's scale error from now on, from `scale` (the
  /// fixes' fit) with this 1-sigma; the position and clock variances grow to match.
  /// Returns the 1-sigma room given to the height (m).
  double enable_ionosphere_state(double scale, double sigma);
  bool ionosphere_state_enabled() const { return cfg_.ionosphere.enabled; }
  /// The estimated scale error of the ionosphere model (0 while the state is off).
  double ionosphere_scale_residual() const { return ionosphere_scale_residual_; }
  /// What the filter adds to a predicted pseudorange beyond the clock: the troposphere
  /// residual mapped to the satellite's elevation and the ionosphere model's delay times
  /// its scale error.
  double residual_delay_m(const RangePrediction& p) const;
  /// What it adds to a predicted carrier rate (m/s, for predicted rates and Dopplers): the
  /// troposphere residual's rate as the elevation changes, and the ionosphere residual's
  /// rate with the carrier's sign.
  double residual_delay_rate_mps(const RangePrediction& p) const;
  const StateMatrix& covariance() const { return kf_.P(); }
  /// 1-sigma position uncertainty, north/east/down (m).
  Eigen::Vector3d position_sigma_ned_m() const;
  /// 1-sigma of the filter's predicted pseudorange and pseudorange rate along a look
  /// (its rows of H through the covariance): what a search for that signal must cover.
  struct PredictionSigma {
    double range_m = 0.0;
    double rate_mps = 0.0;
  };
  PredictionSigma prediction_sigma(const RangePrediction& g) const;
  const Eigen::Vector3d& accel_bias_mps2() const { return ins_.accel_bias_compensation_mps2(); }
  const Eigen::Vector3d& gyro_bias_radps() const { return ins_.gyro_bias_compensation_radps(); }
  bool healthy() const { return kf_.healthy(); }
  const std::string& health_reason() const { return kf_.reason(); }

  /// Antenna position/velocity extrapolated dt seconds ahead at the current velocity (for
  /// measurements stamped between IMU samples).
  Eigen::Vector3d antenna_ecef_at(double t_s) const;
  /// Antenna velocity at t_s (near the navigator's time) with the acceleration of the last
  /// IMU interval: a Doppler tens of milliseconds old in a turn or a climb.
  Eigen::Vector3d antenna_velocity_ecef_at(double t_s) const;

 private:
  /// The lever arm (IMU -> antenna) in NED at the current attitude.
  Eigen::Vector3d lever_arm_ned_m() const;
  /// The rows of H of a pseudorange and of its rate along a look (delay states included when on).
  StateRow pseudorange_row_of(const RangePrediction& g) const;
  StateRow pseudorange_rate_row_of(const RangePrediction& g) const;
  void feed_back();
  StrapdownNed ins_;
  KalmanFilter<kStates> kf_;  ///< error states; the covariance must stay positive definite
  NavigatorConfig cfg_;
  double clock_bias_m_, clock_drift_mps_;  ///< receiver clock model (c * dt, c * dt')
  /// A delay state taken mid-run: the position and clock took the model's error until now
  /// and may have to move by about `vertical_m` in height (1-sigma room), less across.
  void release_position_and_clock(double vertical_m);

  double troposphere_residual_m_ = 0.0;
  double ionosphere_scale_residual_ = 0.0;
  Eigen::Vector3d last_f_b_mps2_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_w_b_radps_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d last_accel_ned_mps2_ =
      Eigen::Vector3d::Zero();  ///< INS velocity change over the last IMU interval / dt
};

/// P0 from the 1-sigma figures.
StateMatrix initial_covariance(const InitialUncertainty& u);

}  // namespace deepnav::aiding
