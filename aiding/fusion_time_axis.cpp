#include "aiding/fusion_time_axis.hpp"

#include <stdexcept>

namespace deepnav::aiding {
namespace {

constexpr double kGpsToUnix_s = 315964800.0;  ///< 1980-01-06 minus 1970-01-01, in seconds

}  // namespace

double fusion_time_s(const ObservationFile& obs, const GpsTime& t) {
  return t.seconds_since(GpsTime{obs.epochs.front().t.week, 0.0});
}

ImuTimeBase parse_imu_time_base(const std::string& name) {
  if (name == "week-seconds") return ImuTimeBase::week_seconds;
  if (name == "gps") return ImuTimeBase::gps_seconds;
  if (name == "unix-gps") return ImuTimeBase::unix_gps;
  throw std::invalid_argument("IMU time base '" + name + "' is not one of week-seconds, gps, unix-gps");
}

void to_fusion_axis(ImuLog& imu, ImuTimeBase base, const ObservationFile& obs) {
  const double week_start_gps_s = obs.epochs.front().t.week * kSecondsPerWeek;
  const double first_sow = obs.epochs.front().t.sow;
  const auto convert = [&](double t) {
    switch (base) {
      case ImuTimeBase::gps_seconds:
        return t - week_start_gps_s;
      case ImuTimeBase::unix_gps:
        return t - kGpsToUnix_s - week_start_gps_s;
      case ImuTimeBase::week_seconds:
        // Seconds of week: the week of the first epoch, or the next one across a rollover.
        return t < first_sow - kSecondsPerWeek / 2 ? t + kSecondsPerWeek : t;
    }
    return t;
  };
  for (ImuSample& s : imu.samples) s.t_s = convert(s.t_s);
  for (ImuGap& g : imu.gaps) g.t_before_s = convert(g.t_before_s), g.t_after_s = convert(g.t_after_s);
}

}  // namespace deepnav::aiding
