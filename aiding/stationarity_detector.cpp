#include "aiding/stationarity_detector.hpp"

namespace deepnav::aiding {

StationarityDetector::StationarityDetector(const StationarityConfig& config, double gravity_mps2,
                                           double gyro_bias_radps)
    : cfg_(config), gravity_mps2_(gravity_mps2), gyro_bias_radps_(gyro_bias_radps) {}

void StationarityDetector::add(const ImuSample& s, double dt_s) {
  if (dt_s <= 0.0) return;
  window_.push_back({s.t_s, s.dv_b_mps / dt_s, s.dtheta_b_rad / dt_s});
  while (!window_.empty() && s.t_s - window_.front().t_s > cfg_.window_s) window_.pop_front();
}

bool StationarityDetector::stationary() const {
  if (!cfg_.enabled || window_.size() < 5 || window_.back().t_s - window_.front().t_s < 0.8 * cfg_.window_s)
    return false;
  Eigen::Vector3d mean_f = Eigen::Vector3d::Zero(), mean_w = Eigen::Vector3d::Zero();
  for (const Entry& e : window_) mean_f += e.f_b_mps2, mean_w += e.w_b_radps;
  mean_f /= static_cast<double>(window_.size());
  mean_w /= static_cast<double>(window_.size());
  if (std::abs(mean_f.norm() - gravity_mps2_) > cfg_.accel_tolerance_mps2 ||
      mean_w.norm() > cfg_.gyro_tolerance_radps + gyro_bias_radps_)
    return false;
  for (const Entry& e : window_)
    if ((e.f_b_mps2 - mean_f).norm() > cfg_.accel_tolerance_mps2 ||
        (e.w_b_radps - mean_w).norm() > cfg_.gyro_tolerance_radps)
      return false;
  return true;
}

}  // namespace deepnav::aiding
