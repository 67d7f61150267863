#include "receiver/pvt/doppler_velocity.hpp"

#include <Eigen/Cholesky>

#include "receiver/pvt/range_model.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {

std::optional<DopplerVelocity> velocity_from_dopplers(const std::map<int, double>& dopplers_hz,
                                                      const std::map<int, Ephemeris>& ephemerides, const GpsTime& t,
                                                      const Eigen::Vector3d& r_ecef_m, const IonoParameters& iono,
                                                      const AtmosphereModels& atmosphere) {
  std::vector<Eigen::Vector4d> rows;
  std::vector<double> rates;
  for (const auto& [prn, doppler_hz] : dopplers_hz) {
    const auto it = ephemerides.find(prn);
    if (it == ephemerides.end()) continue;
    // The clock bias only moves the transmit time by the bias: negligible for a rate.
    const RangePrediction p = predict_range(it->second, t, 0.0, r_ecef_m, Eigen::Vector3d::Zero(), iono, atmosphere);
    // Measured rate less what does not depend on the unknowns: -lf u.v + d is left.
    const double measured_mps = -gps::kL1Wavelength_m * doppler_hz;
    rates.push_back(measured_mps - p.light_time_factor * p.los_ecef.dot(p.v_sat_ecef_mps) + p.satellite_drift_mps -
                    p.carrier_atmosphere_rate_mps);
    Eigen::Vector4d row;
    row << -p.light_time_factor * p.los_ecef, 1.0;
    rows.push_back(row);
  }
  if (rows.size() < 4) return std::nullopt;
  Eigen::MatrixXd H(static_cast<Eigen::Index>(rows.size()), 4);
  Eigen::VectorXd y(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    H.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
    y(static_cast<Eigen::Index>(i)) = rates[i];
  }
  const Eigen::Matrix4d N = H.transpose() * H;
  const Eigen::LDLT<Eigen::Matrix4d> ldlt(N);
  // A singular geometry (satellites in one plane with the receiver) fixes no velocity.
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-9 * ldlt.vectorD().maxCoeff()))
    return std::nullopt;
  const Eigen::Vector4d x = ldlt.solve(H.transpose() * y);
  if (!x.allFinite()) return std::nullopt;
  return DopplerVelocity{x.head<3>(), x(3), static_cast<int>(rows.size())};
}

}  // namespace deepnav
