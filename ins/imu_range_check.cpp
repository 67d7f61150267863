#include "ins/imu_range_check.hpp"

#include <fmt/format.h>

namespace deepnav {
namespace {

/// The largest axis of an increment over dt as a rate, if it exceeds full_scale: a
/// description, else empty.
std::string beyond(const Eigen::Vector3d& increment, double dt_s, double full_scale, double unit, const char* unit_name,
                   const char* sensor) {
  if (full_scale <= 0.0 || dt_s <= 0.0) return {};
  const double peak = increment.cwiseAbs().maxCoeff() / dt_s;
  if (peak <= full_scale) return {};
  return fmt::format("{} {:.4g} {} beyond the grade's +-{:.4g} {}", sensor, peak / unit, unit_name, full_scale / unit,
                     unit_name);
}

}  // namespace

ImuRangeExcess samples_beyond_range(const std::vector<ImuSample>& samples, const ImuErrorModel& grade) {
  ImuRangeExcess out;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const double dt = samples[i].t_s - samples[i - 1].t_s;
    std::string what =
        beyond(samples[i].dtheta_b_rad, dt, grade.gyro.full_scale, imu_units::kDegToRad, "deg/s", "gyro");
    if (what.empty())
      what = beyond(samples[i].dv_b_mps, dt, grade.accel.full_scale, imu_units::kStandardGravity_mps2, "g",
                    "accelerometer");
    if (what.empty()) continue;
    if (!out.first_t_s) {
      out.first_t_s = samples[i].t_s;
      out.first_what = what;
    }
    ++out.samples;
  }
  return out;
}

}  // namespace deepnav
