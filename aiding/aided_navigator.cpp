#include "aiding/aided_navigator.hpp"

#include <cmath>
#include <stdexcept>

#include "aiding/measurement_models.hpp"
#include "ins/frames.hpp"

namespace deepnav::aiding {

StateMatrix initial_covariance(const InitialUncertainty& u) {
  StateVector sigma;
  sigma << u.position_ned_m, u.velocity_ned_mps, u.attitude_rad, u.accel_bias_mps2, u.gyro_bias_radps, u.clock_bias_m,
      u.clock_drift_mps, u.troposphere_zenith_m, u.ionosphere_scale;
  return sigma.cwiseAbs2().asDiagonal();
}

AidedNavigator::AidedNavigator(const NavState& initial, double clock_bias_m, double clock_drift_mps,
                               const NavigatorConfig& config, const InitialUncertainty& uncertainty)
    : ins_(initial),
      kf_(StateVector::Zero(), initial_covariance(uncertainty)),
      cfg_(config),
      clock_bias_m_(clock_bias_m),
      clock_drift_mps_(clock_drift_mps) {
  const double rw = cfg_.troposphere.random_walk_m_per_sqrt_h;
  cfg_.noise.psd(kTropo) = cfg_.troposphere.enabled ? rw * rw / 3600.0 : 0.0;
  const double iono_rw = cfg_.ionosphere.random_walk_per_sqrt_h;
  cfg_.noise.psd(kIono) = cfg_.ionosphere.enabled ? iono_rw * iono_rw / 3600.0 : 0.0;
}

double AidedNavigator::enable_troposphere_state(double zenith_m, double sigma_m) {
  cfg_.troposphere.enabled = true;
  troposphere_residual_m_ = zenith_m;
  kf_.reopen_state(kTropo, sigma_m);
  // The height and the clock have taken the model's error until now (a zenith error z
  // moves them by a few z): let them move back as the state takes it.
  const double room_m = 3.0 * std::max(std::abs(zenith_m), sigma_m);
  release_position_and_clock(room_m);
  const double rw = cfg_.troposphere.random_walk_m_per_sqrt_h;
  cfg_.noise.psd(kTropo) = rw * rw / 3600.0;
  return room_m;
}

double AidedNavigator::enable_ionosphere_state(double scale, double sigma) {
  cfg_.ionosphere.enabled = true;
  // Starting from the fixes' fit takes the model's elevation pattern out of the rows at
  // once: what is left in the height and clock is then a common offset the rows see
  // directly (from 0 the state takes minutes to separate from them).
  ionosphere_scale_residual_ = scale;
  kf_.reopen_state(kIono, sigma);
  // The height and clock took the model's error until now (a zenith delay of a few metres
  // by day): room to move back.
  const double room_m = 5.0 * std::abs(scale) + 1.0;
  release_position_and_clock(room_m);
  const double rw = cfg_.ionosphere.random_walk_per_sqrt_h;
  cfg_.noise.psd(kIono) = rw * rw / 3600.0;
  return room_m;
}

void AidedNavigator::release_position_and_clock(double vertical_m) {
  kf_.add_variance(kPos + 2, vertical_m);
  kf_.add_variance(kClockBias, vertical_m);
  // The horizontal position too: the model's error leans it by a fraction of the vertical
  // shift (its least-squares image over a sky that is not symmetric: 0.5-0.7 m against
  // 6-8 m on the circles), which a filter sure of its horizontal position would unlearn
  // only over tens of seconds (measured: ultra-tight's horizontal RMS 0.35 m 20-60 s after
  // the troposphere state was taken, against 0.13 m with this).
  kf_.add_variance(kPos + 0, vertical_m / 6.0);
  kf_.add_variance(kPos + 1, vertical_m / 6.0);
}

double AidedNavigator::residual_delay_m(const RangePrediction& p) const {
  // A state that is off stays at 0.
  return troposphere_residual_m_ * p.troposphere_mapping + ionosphere_scale_residual_ * p.ionosphere_m;
}

double AidedNavigator::residual_delay_rate_mps(const RangePrediction& p) const {
  return troposphere_residual_m_ * p.troposphere_mapping_rate_per_s -
         ionosphere_scale_residual_ * p.ionosphere_rate_mps;
}

void AidedNavigator::propagate(const ImuSample& sample) {
  const double dt = sample.t_s - ins_.state().t_s;
  const Eigen::Vector3d v_before = ins_.state().v_ned_mps;
  ins_.update(sample);  // validates the time step and the increments
  last_accel_ned_mps2_ = (ins_.state().v_ned_mps - v_before) / dt;
  clock_bias_m_ += clock_drift_mps_ * dt;
  last_f_b_mps2_ = sample.dv_b_mps / dt - ins_.accel_bias_compensation_mps2();
  last_w_b_radps_ = sample.dtheta_b_rad / dt - ins_.gyro_bias_compensation_radps();
  StateMatrix Phi, Qd;
  discretize(error_dynamics(ins_.state(), last_f_b_mps2_, cfg_.noise), cfg_.noise, dt, Phi, Qd);
  kf_.predict(Phi, Qd);
}

Eigen::Vector3d AidedNavigator::antenna_ecef_m() const {
  const NavState& s = ins_.state();
  const Eigen::Vector3d lever_ned = s.q_b_n * cfg_.lever_arm_imu_to_antenna_b_m;
  return wgs84::llh_to_ecef(s.llh) + ned_to_ecef_vector(s.llh, lever_ned);
}

Eigen::Vector3d AidedNavigator::antenna_velocity_ecef_mps() const {
  const NavState& s = ins_.state();
  const Eigen::Vector3d v_ned = s.v_ned_mps + s.q_b_n * last_w_b_radps_.cross(cfg_.lever_arm_imu_to_antenna_b_m);
  return ned_to_ecef_vector(s.llh, v_ned);
}

Eigen::Vector3d AidedNavigator::antenna_ecef_at(double t_s) const {
  return antenna_ecef_m() + antenna_velocity_ecef_mps() * (t_s - ins_.state().t_s);
}

Eigen::Vector3d AidedNavigator::antenna_velocity_ecef_at(double t_s) const {
  const NavState& s = ins_.state();
  return antenna_velocity_ecef_mps() + ned_to_ecef_vector(s.llh, last_accel_ned_mps2_) * (t_s - s.t_s);
}

wgs84::Llh AidedNavigator::antenna_llh() const { return wgs84::ecef_to_llh(antenna_ecef_m()); }

Eigen::Vector3d AidedNavigator::position_sigma_ned_m() const { return kf_.P().diagonal().segment<3>(kPos).cwiseSqrt(); }

StateRow AidedNavigator::pseudorange_row_of(const RangePrediction& g) const {
  return pseudorange_row(ecef_to_ned_vector(ins_.state().llh, g.los_ecef), lever_arm_ned_m(),
                         {.troposphere = cfg_.troposphere.enabled ? std::optional(g.troposphere_mapping) : std::nullopt,
                          .ionosphere = cfg_.ionosphere.enabled ? std::optional(g.ionosphere_m) : std::nullopt});
}

StateRow AidedNavigator::pseudorange_rate_row_of(const RangePrediction& g) const {
  return pseudorange_rate_row(
      ecef_to_ned_vector(ins_.state().llh, g.los_ecef),
      {.troposphere = cfg_.troposphere.enabled ? std::optional(g.troposphere_mapping_rate_per_s) : std::nullopt,
       .ionosphere = cfg_.ionosphere.enabled ? std::optional(-g.ionosphere_rate_mps) : std::nullopt});
}

AidedNavigator::PredictionSigma AidedNavigator::prediction_sigma(const RangePrediction& g) const {
  const StateRow range = pseudorange_row_of(g), rate = pseudorange_rate_row_of(g);
  return {std::sqrt((range * kf_.P() * range.transpose())(0, 0)), std::sqrt((rate * kf_.P() * rate.transpose())(0, 0))};
}

Eigen::Vector3d AidedNavigator::lever_arm_ned_m() const {
  return ins_.state().q_b_n * cfg_.lever_arm_imu_to_antenna_b_m;
}

KalmanUpdate AidedNavigator::update_position_velocity(const Eigen::Vector3d& r_antenna_ecef_m,
                                                      const Eigen::Vector3d& v_antenna_ecef_mps,
                                                      const Eigen::Vector3d& position_sigma_ned_m,
                                                      const Eigen::Vector3d& velocity_sigma_ned_mps,
                                                      double time_offset_s,
                                                      std::optional<double> velocity_time_offset_s) {
  const wgs84::Llh& at = ins_.state().llh;
  Eigen::Matrix<double, 6, 1> z, r;
  z.head<3>() = ecef_to_ned_vector(at, antenna_ecef_at(time_s() + time_offset_s) - r_antenna_ecef_m);
  const Eigen::Vector3d v_ins = velocity_time_offset_s ? antenna_velocity_ecef_at(time_s() + *velocity_time_offset_s)
                                                       : antenna_velocity_ecef_mps();
  z.tail<3>() = ecef_to_ned_vector(at, v_ins - v_antenna_ecef_mps);
  r << position_sigma_ned_m.cwiseAbs2(), velocity_sigma_ned_mps.cwiseAbs2();
  const KalmanUpdate result =
      kf_.update(z, position_velocity_rows(lever_arm_ned_m()), r, {.row_sigma = cfg_.gate_sigma});
  if (result.applied) feed_back();
  return result;
}

KalmanUpdate AidedNavigator::update_zero_velocity(double sigma_mps) {
  // z = predicted - measured = v_ins - 0; dv = -x_vel in the error convention of feed_back.
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(sigma_mps * sigma_mps);
  const KalmanUpdate result = kf_.update(ins_.state().v_ned_mps, velocity_rows(), r, {.row_sigma = cfg_.gate_sigma});
  if (result.applied) feed_back();
  return result;
}

double AidedNavigator::predicted_pseudorange_m(const RangeMeasurement& m) const {
  return m.geometry.pseudorange_m(clock_bias_m() + clock_drift_mps() * m.time_offset_s) + residual_delay_m(m.geometry);
}

double AidedNavigator::predicted_rate_mps(const RangeMeasurement& m) const {
  const RangePrediction& g = m.rate_at_own_time ? m.rate_geometry : m.geometry;
  const double offset = m.rate_at_own_time ? m.rate_time_offset_s : m.time_offset_s;
  return g.pseudorange_rate_mps(antenna_velocity_ecef_at(time_s() + offset), clock_drift_mps()) +
         residual_delay_rate_mps(g);
}

namespace {

/// The rows one navigator update builds: per row its H, z, R and the satellite it came from
/// (pseudorange rows only carry their satellite to the fault monitor; rate rows none).
struct RangeRows {
  std::vector<StateRow> h;
  std::vector<double> z, r;
  std::vector<std::optional<SatelliteId>> pseudorange_of;
};

}  // namespace

KalmanUpdate AidedNavigator::update_ranges(const std::vector<RangeMeasurement>& measurements,
                                           std::vector<SatelliteInnovation>* innovations,
                                           const std::vector<RangeMeasurement>& test_only) {
  const auto append = [&](const RangeMeasurement& m, RangeRows& rows) {
    if (m.pseudorange_m) {
      rows.h.push_back(pseudorange_row_of(m.geometry));
      rows.z.push_back(predicted_pseudorange_m(m) - *m.pseudorange_m);
      rows.r.push_back(m.pseudorange_sigma_m * m.pseudorange_sigma_m);
      rows.pseudorange_of.push_back(m.satellite);
    }
    if (m.rate_mps) {
      rows.h.push_back(pseudorange_rate_row_of(m.rate_at_own_time ? m.rate_geometry : m.geometry));
      rows.z.push_back(predicted_rate_mps(m) - *m.rate_mps);
      rows.r.push_back(m.rate_sigma_mps * m.rate_sigma_mps);
      rows.pseudorange_of.push_back(std::nullopt);
    }
  };
  if (innovations) {
    innovations->clear();
    RangeRows watched;
    for (const auto& m : test_only) append(m, watched);
    for (std::size_t i = 0; i < watched.z.size(); ++i)
      if (watched.pseudorange_of[i])
        innovations->push_back(
            {*watched.pseudorange_of[i], kf_.normalized_innovation(watched.z[i], watched.h[i], watched.r[i]), false});
  }
  RangeRows rows;
  for (const auto& m : measurements) append(m, rows);
  const auto n = static_cast<Eigen::Index>(rows.h.size());
  Eigen::MatrixXd H(n, kStates);
  Eigen::VectorXd zv(n), rv(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    H.row(i) = rows.h[static_cast<std::size_t>(i)];
    zv(i) = rows.z[static_cast<std::size_t>(i)];
    rv(i) = rows.r[static_cast<std::size_t>(i)];
  }
  const KalmanUpdate result = kf_.update(zv, H, rv, {.row_sigma = cfg_.gate_sigma});
  if (innovations) {
    for (std::size_t i = 0; i < result.normalized_innovations.size(); ++i)
      if (rows.pseudorange_of[i])
        innovations->push_back({*rows.pseudorange_of[i], result.normalized_innovations[i], result.row_rejected[i]});
  }
  if (result.applied) feed_back();
  return result;
}

void AidedNavigator::feed_back() {
  const StateVector& x = kf_.x();
  ins_.correct_position(-x.segment<3>(kPos));
  ins_.correct_velocity(-x.segment<3>(kVel));
  ins_.correct_attitude(-x.segment<3>(kAtt));
  ins_.set_bias_compensation(ins_.accel_bias_compensation_mps2() + x.segment<3>(kAccelBias),
                             ins_.gyro_bias_compensation_radps() + x.segment<3>(kGyroBias));
  clock_bias_m_ -= x(kClockBias);
  clock_drift_mps_ -= x(kClockDrift);
  troposphere_residual_m_ -= x(kTropo);
  ionosphere_scale_residual_ -= x(kIono);
  kf_.clear_state();
}

}  // namespace deepnav::aiding
