#include "ins/sim/trajectory_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "ins/attitude_rates.hpp"
#include "ins/cubic_spline.hpp"
#include "ins/frames.hpp"
#include "ins/rotations.hpp"
#include "ins/wgs84.hpp"

namespace deepnav {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
// What a GPS receiver's trajectory can be: from below the Dead Sea shore (and the deepest
// mines) to beyond the GPS orbits, at most 12 km/s (faster than escape velocity).
constexpr double kMinHeight_m = -12000.0;
constexpr double kMaxHeight_m = 1.0e8;
constexpr double kMaxSpeed_mps = 1.2e4;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) {
    const auto b = field.find_first_not_of(" \t\r");
    const auto e = field.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
  }
  return out;
}

class CsvTrajectory : public Trajectory {
 public:
  CsvTrajectory(std::string path, CubicSpline position, std::optional<CubicSpline> euler)
      : path_(std::move(path)), position_(std::move(position)), euler_(std::move(euler)) {}

  TrajectoryState at(double t) const override {
    Eigen::VectorXd r, v, a;
    position_.evaluate(t, r, v, a);
    TrajectoryState s;
    s.t_s = t;
    s.r_ecef_m = r;
    s.v_ecef_mps = v;
    s.a_ecef_mps2 = a;
    const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
    const Eigen::Matrix3d C_en = C_e_n(llh.lat_rad, llh.lon_rad);
    s.v_ned_mps = C_en * s.v_ecef_mps;
    s.a_ned_mps2 = C_en * s.a_ecef_mps2 - transport_rate_ned_radps(llh, s.v_ned_mps).cross(s.v_ned_mps);
    s.q_b_n = attitude(t);
    // Differences need the attitude two steps on both sides of tc, inside the file's span:
    // a step that fits a file shorter than four 2 ms steps, and each point clamped into the
    // span against rounding ((t0 + 2h) - 2h can land an ulp before t0).
    const double begin = position_.t_begin(), end = position_.t_end();
    const double h = std::min(2e-3, (end - begin) / 5);
    const double tc = std::clamp(t, begin + 2 * h, end - 2 * h);
    const auto inside = [&](double x) { return attitude(std::clamp(x, begin, end)); };
    const AttitudeRates rates = attitude_rates(inside, tc, attitude(tc), h);
    s.w_nb_b_radps = rates.w_nb_b_radps;
    s.dw_nb_b_radps2 = rates.dw_nb_b_radps2;
    return s;
  }
  /// File times are trajectory times (seconds from the scenario start).
  double duration_s() const override { return position_.t_end(); }
  std::string description() const override { return "CSV trajectory " + path_; }

 private:
  Eigen::Quaterniond attitude(double t) const {
    EulerAngles e;
    if (euler_) {
      const Eigen::VectorXd a = euler_->value(t);
      e = EulerAngles{a(0), a(1), a(2)};
    } else {
      Eigen::VectorXd r, v, acc;
      position_.evaluate(t, r, v, acc);
      const wgs84::Llh llh = wgs84::ecef_to_llh(r);
      const Eigen::Vector3d v_ned = C_e_n(llh.lat_rad, llh.lon_rad) * Eigen::Vector3d(v);
      const double vh = v_ned.head<2>().norm();
      if (v_ned.norm() >= 0.1) {
        e.yaw_rad = std::atan2(v_ned.y(), v_ned.x());
        e.pitch_rad = std::atan2(-v_ned.z(), vh);
      }
    }
    return quaternion_from_euler(e);
  }

  std::string path_;
  CubicSpline position_;
  std::optional<CubicSpline> euler_;
};

}  // namespace

std::unique_ptr<Trajectory> load_csv_trajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open trajectory file '" + path + "'");
  return load_csv_trajectory(in, path);
}

std::unique_ptr<Trajectory> load_csv_trajectory(std::istream& in, const std::string& path) {
  auto fail = [&](int line, const std::string& what) -> void {
    throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
  };
  std::string line;
  int line_no = 0;
  std::vector<std::string> header;
  while (header.empty() && std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    header = split(line);
  }
  if (header.empty()) fail(line_no, "empty file: expected a header line naming the columns");
  const std::vector<std::string> geo{"t_s", "lat_deg", "lon_deg", "height_m"};
  const std::vector<std::string> ecef{"t_s", "x_ecef_m", "y_ecef_m", "z_ecef_m"};
  const std::vector<std::string> att{"roll_deg", "pitch_deg", "yaw_deg"};
  const bool is_geo =
      std::equal(geo.begin(), geo.end(), header.begin(), header.begin() + std::min<std::size_t>(4, header.size())) &&
      header.size() >= 4;
  const bool is_ecef =
      std::equal(ecef.begin(), ecef.end(), header.begin(), header.begin() + std::min<std::size_t>(4, header.size())) &&
      header.size() >= 4;
  const bool has_att = header.size() == 7 && std::equal(att.begin(), att.end(), header.begin() + 4);
  if (!(is_geo || is_ecef) || !(header.size() == 4 || has_att)) {
    fail(line_no,
         "expected the header 't_s,lat_deg,lon_deg,height_m' or 't_s,x_ecef_m,y_ecef_m,z_ecef_m', "
         "optionally followed by ',roll_deg,pitch_deg,yaw_deg'");
  }
  std::vector<double> times;
  std::vector<Eigen::Vector3d> positions, angles;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    const auto fields = split(line);
    if (fields.size() != header.size()) {
      fail(line_no, "expected " + std::to_string(header.size()) + " columns, got " + std::to_string(fields.size()));
    }
    std::vector<double> v;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      std::size_t used = 0;
      double x = 0.0;
      try {
        x = std::stod(fields[i], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != fields[i].size() || fields[i].empty())
        fail(line_no, "column '" + header[i] + "': '" + fields[i] + "' is not a number");
      if (!std::isfinite(x)) fail(line_no, "column '" + header[i] + "': value is not finite");
      v.push_back(x);
    }
    if (!times.empty() && !(v[0] > times.back())) fail(line_no, "time must increase strictly");
    times.push_back(v[0]);
    if (is_geo) {
      if (std::abs(v[1]) > 90.0) fail(line_no, "lat_deg out of [-90, 90]");
      if (!(v[3] >= kMinHeight_m && v[3] <= kMaxHeight_m))
        fail(line_no, fmt::format("height_m {:g} is outside [{:g}, {:g}] m", v[3], kMinHeight_m, kMaxHeight_m));
      positions.push_back(wgs84::llh_to_ecef(wgs84::Llh{v[1] * kDeg, v[2] * kDeg, v[3]}));
    } else {
      positions.emplace_back(v[1], v[2], v[3]);
      const double r = positions.back().norm();
      const double r_min = wgs84::kSemiMinorAxis_m + kMinHeight_m, r_max = wgs84::kSemiMajorAxis_m + kMaxHeight_m;
      if (!(r >= r_min && r <= r_max))
        fail(line_no,
             fmt::format("position is {:.6g} m from the Earth's centre, not in [{:g}, {:g}] m (near the Earth)", r,
                         r_min, r_max));
    }
    // Rows are samples of one motion: a jump between two of them (a wrong sign, a lost
    // digit) would make the receiver faster than anything that carries one.
    if (positions.size() >= 2) {
      const double dt = times.back() - times[times.size() - 2];
      const double speed = (positions.back() - positions[positions.size() - 2]).norm() / dt;
      if (!(speed <= kMaxSpeed_mps))
        fail(line_no,
             fmt::format("the position moves {:.6g} m in {:g} s from the previous row ({:.4g} m/s), faster "
                         "than {:g} m/s",
                         (positions.back() - positions[positions.size() - 2]).norm(), dt, speed, kMaxSpeed_mps));
    }
    if (has_att) {
      Eigen::Vector3d e(v[4] * kDeg, v[5] * kDeg, v[6] * kDeg);
      if (!angles.empty()) {  // unwrap yaw (and roll) so the spline does not swing through 360 degrees
        for (int k : {0, 2}) e(k) = angles.back()(k) + wrap_pi(e(k) - angles.back()(k));
      }
      angles.push_back(e);
    }
  }
  if (times.size() < 4) fail(line_no, "need at least 4 rows, got " + std::to_string(times.size()));
  Eigen::MatrixXd p(3, static_cast<Eigen::Index>(times.size()));
  for (std::size_t i = 0; i < positions.size(); ++i) p.col(static_cast<Eigen::Index>(i)) = positions[i];
  std::optional<CubicSpline> euler;
  if (has_att) {
    Eigen::MatrixXd a(3, static_cast<Eigen::Index>(times.size()));
    for (std::size_t i = 0; i < angles.size(); ++i) a.col(static_cast<Eigen::Index>(i)) = angles[i];
    euler.emplace(times, a);
  }
  return std::make_unique<CsvTrajectory>(path, CubicSpline(times, p), std::move(euler));
}

}  // namespace deepnav
