#include "ins/attitude_rates.hpp"

namespace deepnav {

AttitudeRates attitude_rates(const std::function<Eigen::Quaterniond(double)>& q_b_n_of_t, double t,
                             const Eigen::Quaterniond& q_at_t, double h) {
  Eigen::Vector4d q[5];
  for (int k = -2; k <= 2; ++k) {
    q[k + 2] = k == 0 ? q_at_t.coeffs() : q_b_n_of_t(t + k * h).coeffs();
    if (q[k + 2].dot(q_at_t.coeffs()) < 0.0) q[k + 2] *= -1.0;  // same hemisphere as q(t)
  }
  const Eigen::Vector4d d1 = (q[0] - 8.0 * q[1] + 8.0 * q[3] - q[4]) / (12.0 * h);
  const Eigen::Vector4d d2 = (-q[0] + 16.0 * q[1] - 30.0 * q[2] + 16.0 * q[3] - q[4]) / (12.0 * h * h);
  const Eigen::Quaterniond qc = q_at_t.conjugate();
  AttitudeRates r;
  r.w_nb_b_radps = 2.0 * (qc * Eigen::Quaterniond(d1)).vec();
  r.dw_nb_b_radps2 = 2.0 * (qc * Eigen::Quaterniond(d2)).vec();
  return r;
}

}  // namespace deepnav
