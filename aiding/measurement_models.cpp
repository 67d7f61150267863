#include "aiding/measurement_models.hpp"

#include <algorithm>
#include <cmath>

#include "ins/rotations.hpp"
#include "receiver/gnss_receiver.hpp"
#include "receiver/tracking/e1_tracking_channel.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav::aiding {
namespace {

constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;
// Rate sigma floors (m/s). Phase windows: what the model leaves out inside a window (the
// Doppler's second derivative around the window's middle, the INS velocity error there).
// The receiver clock's white frequency noise is common to every channel (3 cm/s over
// 100 ms for a TCXO with h0 = 2e-21); the clock drift state takes it, its random walk
// moves it by that much within a window. Frequency discriminator: more dynamics left over
// across one integration.
constexpr double kPhaseRateFloor_mps = 0.005;
constexpr double kDiscriminatorRateFloor_mps = 0.02;
constexpr double kScalarRateFloor_mps = 0.02;

}  // namespace

StateRow antenna_position_row(const Eigen::Vector3d& u_ned, const Eigen::Vector3d& lever_ned) {
  // d(antenna) = dr - [(C l) x] eps, so a row u^T on the antenna error is
  // u^T on dr and -u^T [(C l) x] on eps.
  StateRow h = StateRow::Zero();
  h.segment<3>(kPos) = u_ned.transpose();
  h.segment<3>(kAtt) = -u_ned.transpose() * skew(lever_ned);
  return h;
}

Eigen::Matrix<double, 6, kStates> position_velocity_rows(const Eigen::Vector3d& lever_ned) {
  Eigen::Matrix<double, 6, kStates> H = Eigen::Matrix<double, 6, kStates>::Zero();
  for (int i = 0; i < 3; ++i) {
    H.row(i) = antenna_position_row(Eigen::Vector3d::Unit(i), lever_ned);
    H(3 + i, kVel + i) = 1.0;
  }
  return H;
}

Eigen::Matrix<double, 3, kStates> velocity_rows() {
  Eigen::Matrix<double, 3, kStates> H = Eigen::Matrix<double, 3, kStates>::Zero();
  H.block<3, 3>(0, kVel).setIdentity();
  return H;
}

StateRow pseudorange_row(const Eigen::Vector3d& los_ned, const Eigen::Vector3d& lever_ned,
                         const DelayStateColumns& delay) {
  // The range falls as the antenna moves towards the satellite: d(rho) = -u . d(r).
  StateRow h = -antenna_position_row(los_ned, lever_ned);
  h(kClockBias) = 1.0;
  if (delay.troposphere) h(kTropo) = *delay.troposphere;
  if (delay.ionosphere) h(kIono) = *delay.ionosphere;
  return h;
}

StateRow pseudorange_rate_row(const Eigen::Vector3d& los_ned, const DelayStateColumns& delay) {
  StateRow h = StateRow::Zero();
  h.segment<3>(kVel) = -los_ned.transpose();
  h(kClockDrift) = 1.0;
  if (delay.troposphere) h(kTropo) = *delay.troposphere;
  if (delay.ionosphere) h(kIono) = *delay.ionosphere;
  return h;
}

Eigen::Vector3d pvt_position_sigma_ned_m(double hdop, double vdop, double scale_m) {
  const double h = std::max(1.0, hdop * scale_m / std::sqrt(2.0));
  const double v = std::max(1.5, vdop * scale_m);
  return {h, h, v};
}

double scalar_pseudorange_sigma_m(const RangeErrorModel& errors, double elevation_rad, double cn0_dbhz,
                                  double row_interval_s) {
  return std::sqrt(errors.model_variance_per_row_m2(elevation_rad, row_interval_s) +
                   errors.thermal_variance_m2(cn0_dbhz));
}

double scalar_rate_sigma_mps(double cn0_dbhz, double pll_bandwidth_hz, double coherent_s) {
  const double cn0 = std::pow(10.0, std::max(cn0_dbhz, 20.0) / 10.0);
  const double phase_var_rad2 = pll_bandwidth_hz / cn0 * (1.0 + 1.0 / (2.0 * coherent_s * cn0));
  const double rate_mps = std::sqrt(2.0 * phase_var_rad2) / (2.0 * M_PI * kDopplerWindow_s) * gps::kL1Wavelength_m;
  return std::hypot(rate_mps, kScalarRateFloor_mps);
}

double discriminator_pseudorange_sigma_m(const RangeErrorModel& errors, double elevation_rad, double cn0_dbhz,
                                         double integration_s, double spacing_chips, double piece_s) {
  // The model terms are shared by every integration of the same second (range_weight.hpp).
  const double code_sigma = code_sigma_chips(cn0_dbhz, integration_s, spacing_chips, piece_s) * kChip_m;
  return std::sqrt(code_sigma * code_sigma + errors.model_variance_per_row_m2(elevation_rad, integration_s));
}

double e1_discriminator_pseudorange_sigma_m(const RangeErrorModel& errors, double elevation_rad, double cn0_dbhz,
                                            double integration_s, double spacing_chips, double code_sigma_floor_chips) {
  const double code_sigma =
      std::max(e1_code_sigma_chips(cn0_dbhz, integration_s, spacing_chips), code_sigma_floor_chips) * kChip_m;
  return std::sqrt(code_sigma * code_sigma + errors.model_variance_per_row_m2(elevation_rad, integration_s));
}

double discriminator_rate_sigma_mps(double cn0_dbhz, double integration_s, double rate_window_s, int pairs) {
  // One integration's phase noise at both ends of the window or of the discriminator's
  // span (adjoining windows share an end, so their errors are negatively correlated:
  // taking them as independent understates what a run of windows says).
  const bool phase_window = rate_window_s > 0.0;
  const double sigma_hz = mean_frequency_sigma_hz(phase_variance_rad2(cn0_dbhz, integration_s),
                                                  phase_window ? rate_window_s : integration_s) /
                          std::sqrt(static_cast<double>(std::max(pairs, 1)));
  return std::hypot(sigma_hz * gps::kL1Wavelength_m, phase_window ? kPhaseRateFloor_mps : kDiscriminatorRateFloor_mps);
}

double code_sigma_chips(double cn0_dbhz, double t_s, double spacing_chips, double piece_s) {
  const double cn0_hz = std::pow(10.0, cn0_dbhz / 10.0);
  const double piece_snr = cn0_hz * (piece_s > 0.0 ? piece_s : t_s);
  return std::sqrt(spacing_chips / (4.0 * cn0_hz * t_s) * (1.0 + 2.0 / ((2.0 - spacing_chips) * piece_snr)));
}

double e1_pilot_cn0_dbhz(double cn0_dbhz) { return cn0_dbhz + 10.0 * std::log10(e1_pilot_power_fraction()); }

double e1_signal_cn0_dbhz(double pilot_cn0_dbhz) {
  return pilot_cn0_dbhz - 10.0 * std::log10(e1_pilot_power_fraction());
}

double e1_code_sigma_chips(double cn0_dbhz, double t_s, double spacing_chips) {
  return code_sigma_chips(e1_pilot_cn0_dbhz(cn0_dbhz), t_s, spacing_chips) / std::sqrt(3.0);
}

double phase_variance_rad2(double cn0_dbhz, double t_s) {
  const double snr = std::pow(10.0, cn0_dbhz / 10.0) * t_s;
  return 1.0 / (2.0 * snr) * (1.0 + 1.0 / (2.0 * snr));
}

double mean_frequency_sigma_hz(double phase_var_rad2, double span_s) {
  return std::sqrt(2.0 * phase_var_rad2) / (2.0 * M_PI * span_s);
}

}  // namespace deepnav::aiding
