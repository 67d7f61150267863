#pragma once
// IMU error model per sensor triad and the named IMU grades (data/imu_grades.yaml).
// Everything here is SI: gyro quantities in rad, rad/s, rad/sqrt(s); accelerometer
// quantities in m/s, m/s^2, m/s/sqrt(s). deg/h, ug, deg/sqrt(h), m/s/sqrt(h) and ppm
// appear only in the YAML file and are converted on loading.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace deepnav {

/// Error statistics of one sensor triad (three gyros or three accelerometers), as a
/// datasheet states them. Turn-on quantities (bias_sigma, scale factor, misalignment)
/// are drawn once per run from the seeded generator; `bias` is a deterministic part
/// added on top (the paper 003 [docs/references.md] preset uses it for its stated 100 ug / 0.1 deg/h).
struct TriadErrorSpec {
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();  ///< deterministic bias, rad/s or m/s^2
  double bias_sigma = 0.0;                         ///< turn-on bias 1 sigma per axis
  double bias_instability_sigma = 0.0;             ///< steady-state 1 sigma of the Gauss-Markov bias
  double bias_correlation_time_s = 0.0;            ///< its correlation time; 0 disables the process
  double random_walk = 0.0;                        ///< ARW rad/sqrt(s) or VRW m/s/sqrt(s) (white rate noise)
  double scale_factor_sigma = 0.0;                 ///< 1 sigma per axis, dimensionless (1e-6 = 1 ppm)
  double misalignment_sigma_rad = 0.0;             ///< 1 sigma of each off-diagonal axis misalignment
  double quantization = 0.0;                       ///< LSB of the increment (rad or m/s); 0 = none
  double full_scale = 0.0;                         ///< measurement range, +- rad/s or m/s^2 per axis; 0 = not given
};

/// Both triads and the output rate.
struct ImuErrorModel {
  TriadErrorSpec gyro;
  TriadErrorSpec accel;
  double sample_rate_hz = 100.0;
};

/// The per-run fixed part of a triad's errors, drawn from a TriadErrorSpec.
/// Measured = (I + diag(scale_factor) + misalignment) * true + bias + noise.
struct TriadErrorDraw {
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d scale_factor = Eigen::Vector3d::Zero();
  Eigen::Matrix3d misalignment = Eigen::Matrix3d::Zero();  ///< zero diagonal
};

/// A named grade from data/imu_grades.yaml.
struct ImuGrade {
  std::string name;
  std::string description;
  ImuErrorModel model;
};

/// Loads every grade in a YAML file. Throws std::runtime_error naming the file, the
/// grade and the field when something is missing, negative or of the wrong type.
std::vector<ImuGrade> load_imu_grades(const std::string& yaml_path);
/// Loads one grade by name; throws naming the file and listing the names it has.
ImuGrade load_imu_grade(const std::string& yaml_path, const std::string& name);

/// Unit conversions used at the edges (YAML, CLI, reports).
namespace imu_units {
inline constexpr double kStandardGravity_mps2 = 9.80665;
inline constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
inline constexpr double kDegPerHour_to_radps = kDegToRad / 3600.0;
inline constexpr double kMicroG_to_mps2 = 1e-6 * kStandardGravity_mps2;
inline constexpr double kDegPerSqrtHour_to_radpsqrts = kDegToRad / 60.0;  // sqrt(3600 s) = 60
inline constexpr double kMpsPerSqrtHour_to_mpspsqrts = 1.0 / 60.0;
inline constexpr double kPpm = 1e-6;
}  // namespace imu_units

}  // namespace deepnav
