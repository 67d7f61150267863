#pragma once
// IMU data files (CSV). One header line names the columns with their units:
//   increments: t_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps
//               (delta-theta and delta-v over the interval ending at t_s)
//   rates:      t_s,wx_radps,wy_radps,wz_radps,fx_mps2,fy_mps2,fz_mps2
//               (angular rate and specific force held over the interval ending at t_s)
// Lines starting with '#' before the header are comments; the writer records the
// nominal rate there as "# sample_rate_hz=100".
//
// Reader rules: wrong header (names or units), wrong column count, unparsable,
// NaN or infinite values, and timestamps that repeat or go backwards are errors
// that name the file and line, and so are samples beyond any sensor's range (below). A gap (an interval longer than 1.5x the nominal one)
// is not an error: it is listed in ImuLog::gaps and never interpolated across; for
// rate files the sample after a gap is integrated over one nominal interval only.
#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "ins/imu_sample.hpp"

namespace deepnav {

enum class ImuFileForm { kIncrements, kRates };

/// Beyond what any inertial sensor measures, per axis: 10000 deg/s of angular rate (gyros
/// reach a few thousand) and 10000 m/s^2 of specific force (about 1000 g; tactical and
/// navigation accelerometers stop at 50-100 g). A sample beyond either is corrupt data and
/// an error naming the file, line and column.
inline constexpr double kMaxImuRate_radps = 10000.0 * 3.14159265358979323846 / 180.0;
inline constexpr double kMaxImuSpecificForce_mps2 = 1.0e4;

struct ImuGap {
  std::size_t line = 0;     ///< line of the first sample after the gap (1-based)
  double t_before_s = 0.0;  ///< last sample time before the gap
  double t_after_s = 0.0;   ///< first sample time after it
};

struct ImuLog {
  ImuFileForm form = ImuFileForm::kIncrements;
  double nominal_interval_s = 0.0;  ///< from the sample_rate_hz comment, else the median interval
  std::vector<ImuSample> samples;   ///< always as increments
  std::vector<ImuGap> gaps;
  std::string source;  ///< the file it was read from (for messages)
};

/// Writes through an OutputFile (output_file.hpp): `path` appears only when complete;
/// throws std::runtime_error naming the path on failure (the partial file is removed).
/// Values are written with the shortest representation that reads back exactly.
void write_imu_csv(const std::string& path, const std::vector<ImuSample>& samples, ImuFileForm form,
                   double sample_rate_hz);

/// Reads and validates an IMU CSV file (see the rules above).
ImuLog read_imu_csv(const std::string& path);
/// Same from a stream; `name` stands for the file in messages and ImuLog::source.
ImuLog read_imu_csv(std::istream& in, const std::string& name);

}  // namespace deepnav
