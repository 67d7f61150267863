#pragma once
// IMU logs as recorders write them, read into an ImuLog (increments in the body frame):
//  - deepnav: our CSV (ins/imu_file.hpp, strict);
//  - csv:     a generic delimited text file with a column map naming which column is
//             the time, each accelerometer and each gyro axis ("ax,ay,az,gx,gy,gz,t";
//             "-" for a column to ignore), their units (g or m/s^2; deg/s or rad/s; for
//             increments m/s and rad, or deg) and whether they are rates or increments;
//  - kf-gins: the KF-GINS text layout: time (s), angle increments x y z (rad), velocity
//             increments x y z (m/s), separated by blanks or commas.
// Time: t = offset + scale x (the time column), in whatever time base the caller uses
// (the fuse command takes GPS seconds of week, GPS seconds or GPS seconds since 1970);
// the offset includes any constant IMU-to-GNSS time offset.
//
// A real log is irregular, and the reader says how (ImuLogReport, warnings):
//  - a row repeating the previous row whole (time and values) is the same row written
//    twice: dropped, counted, warned about;
//  - a row at the previous row's time with other values: two samples cannot share a time
//    and which one is right cannot be told: dropped, counted, warned about;
//  - a row whose time goes back before the previous row's (rows out of order, a logger's
//    clock re-set) is an error naming both lines: the log's order cannot be trusted past it;
//  - a row whose sensor values repeat the previous row's at a new time is data (a still
//    IMU of fine resolution, a simulator's, a logger reading its IMU faster than the IMU
//    samples): kept, counted;
//  - a cut first or last line (a log started or stopped mid-line: too few fields) is
//    skipped, counted; anywhere else it is an error;
//  - irregular intervals are integrated as they come (a rate is held over the interval
//    ending at its time); an interval over gap_factor x the nominal interval is a gap,
//    listed and never interpolated across (the sample after it covers one nominal
//    interval).
// Errors (no such file, a field that is not a number, a bad column map, time going back,
// no samples) throw std::runtime_error naming the file, the line and the field or column.
#include <Eigen/Core>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "ins/imu_file.hpp"

namespace deepnav {

enum class ImuLogFormat { deepnav, csv, kf_gins };
enum class ImuQuantity { rates, increments };

struct ImuLogOptions {
  ImuLogFormat format = ImuLogFormat::deepnav;
  /// csv: what each column holds, comma separated: t, ax ay az, gx gy gz, or - (ignored).
  std::string columns = "t,ax,ay,az,gx,gy,gz";
  ImuQuantity quantity = ImuQuantity::rates;  ///< csv: rates or increments
  /// csv accelerometer unit: "g" or "m/s^2" (rates); increments "m/s" or "g*s".
  std::string accel_unit = "m/s^2";
  /// csv gyro unit: "deg/s" or "rad/s" (rates); increments "rad" or "deg".
  std::string gyro_unit = "rad/s";
  double time_scale = 1.0;                ///< seconds per unit of the time column
  double time_offset_s = 0.0;             ///< added after scaling (time base origin + IMU-to-GNSS offset)
  std::optional<double> nominal_rate_hz;  ///< else the mean rate of the kept samples
  double gap_factor = 3.0;                ///< interval > gap_factor / rate: a gap
};

struct ImuLogReport {
  std::string format;
  int lines = 0;            ///< lines in the file
  int header_lines = 0;     ///< comment and header lines
  int rows = 0;             ///< data rows read
  int samples = 0;          ///< samples kept
  int duplicate_rows = 0;   ///< the previous row again, time and values (dropped)
  int repeated_time = 0;    ///< the previous row's time with other values (dropped)
  int repeated_values = 0;  ///< the previous row's values at a new time (kept: data)
  int truncated_lines = 0;  ///< cut first or last line (skipped)
  double nominal_interval_s = 0.0;
  double min_interval_s = 0.0, max_interval_s = 0.0, mean_interval_s = 0.0;
  double first_t_s = 0.0, last_t_s = 0.0;
  double time_scale = 1.0, time_offset_s = 0.0;
  std::vector<ImuGap> gaps;
  /// What a user should know about the log (each names the file and the first line).
  std::vector<std::string> warnings;
};

struct ImuLogRead {
  ImuLog log;
  ImuLogReport report;
};

/// Reads an IMU log in any of the formats above.
ImuLogRead read_imu_log(const std::string& path, const ImuLogOptions& options);
/// Same from a stream (csv and kf-gins; `name` stands for the file in messages).
ImuLogRead read_imu_log(std::istream& in, const std::string& name, const ImuLogOptions& options);

/// "deepnav", "csv", "kf-gins" (throws std::invalid_argument listing them otherwise).
ImuLogFormat parse_imu_log_format(const std::string& name);

/// How the IMU sits in the body: its axes turned by roll, pitch, yaw (deg, applied
/// yaw-pitch-roll as for a body in the navigation frame: C_b_imu = Rz(yaw) Ry(pitch)
/// Rx(roll), a vector in IMU axes is C_b_imu times it in body axes), and where it and the
/// antenna are from the body's origin (body axes, m).
struct ImuMounting {
  Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();
  Eigen::Vector3d imu_position_b_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d antenna_position_b_m = Eigen::Vector3d::Zero();

  Eigen::Matrix3d C_b_imu() const;
  /// The lever arm from the IMU to the antenna, body axes.
  Eigen::Vector3d lever_arm_imu_to_antenna_b_m() const { return antenna_position_b_m - imu_position_b_m; }
};

/// Turns every increment of the log from IMU axes into body axes.
void apply_mounting(ImuLog& log, const ImuMounting& mounting);

}  // namespace deepnav
