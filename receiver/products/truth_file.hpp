#pragma once
// The synthesizer's receiver truth (truth.csv) for scoring a run: position and velocity
// at receiver clock time t_s (seconds since the first sample), linearly interpolated.
#include <Eigen/Core>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace deepnav {

struct TruthSample {
  double t_s = 0.0;
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_ecef_mps = Eigen::Vector3d::Zero();
  /// True GPS seconds of week at t_s (the receiver clock's reading gps_sow minus its
  /// clock_bias_s), when the file carries both columns.
  std::optional<double> true_sow;
};

class TruthFile {
 public:
  /// Throws std::runtime_error naming the file and line for malformed input.
  explicit TruthFile(const std::string& path);
  /// Same from a stream; `name` stands for the file in messages.
  TruthFile(std::istream& in, const std::string& name);
  /// nullopt outside the file's time span.
  std::optional<TruthSample> at(double t_s) const;

 private:
  void read(std::istream& in, const std::string& name);
  std::vector<TruthSample> rows_;
};

}  // namespace deepnav
