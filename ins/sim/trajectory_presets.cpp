#include "ins/sim/trajectory_presets.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ins/attitude_rates.hpp"
#include "ins/frames.hpp"
#include "ins/rotations.hpp"

namespace deepnav {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kKmh = 1.0 / 3.6;
constexpr double kStandardGravity = 9.80665;

/// Horizontal kinematics in the tangent plane at one time.
struct PlanarState {
  Eigen::Vector2d p_m = Eigen::Vector2d::Zero();  ///< north, east
  double course_rad = 0.0;
  double speed_mps = 0.0;
  double accel_mps2 = 0.0;
  double turn_rate_radps = 0.0;
  /// Turn rate the bank angle follows: equal to turn_rate_radps except within half a
  /// roll-reversal time of a change of turn rate, where it blends smoothly (a bank that
  /// jumped would be an infinite roll rate no IMU could report).
  double bank_turn_rate_radps = 0.0;
};

/// Quintic smoothstep: 0 -> 1 on [0, 1] with zero first and second derivatives at both ends.
double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}

/// Bank turn rate at `time_in_segment` of a segment of length `duration`, blending
/// over `reversal_s` centred on each end with the neighbouring segments' rates.
double blended_turn_rate(double prev, double cur, double next, double time_in_segment, double duration,
                         double reversal_s) {
  if (reversal_s <= 0.0) return cur;
  const double half = 0.5 * reversal_s;
  if (time_in_segment < half) return prev + (cur - prev) * smoothstep((time_in_segment + half) / reversal_s);
  const double to_end = duration - time_in_segment;
  if (to_end < half) return cur + (next - cur) * smoothstep((half - to_end) / reversal_s);
  return cur;
}

/// Advances a planar state by dt within one segment (closed form).
PlanarState advance(const PlanarState& s, const PathSegment& seg, double dt) {
  PlanarState out = s;
  out.accel_mps2 = seg.accel_mps2;
  out.turn_rate_radps = seg.turn_rate_radps;
  const double w = seg.turn_rate_radps;
  if (w == 0.0) {
    const double dist = s.speed_mps * dt + 0.5 * seg.accel_mps2 * dt * dt;
    out.p_m += dist * Eigen::Vector2d(std::cos(s.course_rad), std::sin(s.course_rad));
    out.speed_mps = s.speed_mps + seg.accel_mps2 * dt;
  } else {
    // Constant speed arc: d(p)/dt = v (cos psi, sin psi), psi = psi0 + w t.
    const double v = s.speed_mps;
    const double psi1 = s.course_rad + w * dt;
    out.p_m +=
        (v / w) * Eigen::Vector2d(std::sin(psi1) - std::sin(s.course_rad), std::cos(s.course_rad) - std::cos(psi1));
    out.course_rad = psi1;
  }
  return out;
}

class PathTrajectory : public Trajectory {
 public:
  explicit PathTrajectory(PathSpec spec) : spec_(std::move(spec)) {
    r0_ecef_ = wgs84::llh_to_ecef(spec_.start);
    C_t_e_ = C_n_e(spec_.start.lat_rad, spec_.start.lon_rad);
    for (const auto& seg : spec_.segments) {
      if (seg.turn_rate_radps != 0.0 && seg.accel_mps2 != 0.0) {
        throw std::invalid_argument("trajectory '" + spec_.name + "': a turning segment must have constant speed");
      }
    }
    if (spec_.segments.empty()) spec_.segments.push_back(PathSegment{std::numeric_limits<double>::infinity(), 0, 0});
  }

  TrajectoryState at(double t) const override {
    TrajectoryState s = kinematics(t);
    // Body rate w.r.t. local NED from central differences of the attitude.
    const AttitudeRates rates = attitude_rates([this](double x) { return attitude(x); }, t, s.q_b_n);
    s.w_nb_b_radps = rates.w_nb_b_radps;
    s.dw_nb_b_radps2 = rates.dw_nb_b_radps2;
    return s;
  }

  double duration_s() const override { return spec_.duration_s; }
  std::string description() const override { return spec_.name; }

 private:
  /// Planar state at time t (t may be negative: the first segment extends backwards).
  PlanarState planar(double t) const {
    PlanarState s;
    s.course_rad = spec_.heading_rad;
    s.speed_mps = spec_.speed_mps;
    const auto& segs = spec_.segments;
    const PathSegment straight_on{std::numeric_limits<double>::infinity(), 0.0, 0.0};
    if (t <= 0.0)
      return with_bank_rate(advance(s, segs.front(), t), segs.front().turn_rate_radps, segs.front(), next_turn_rate(0),
                            t, segs.front().duration_s);
    double elapsed = 0.0;
    std::size_t i = 0;
    double prev_rate = segs.front().turn_rate_radps;  // the first segment extends backwards unchanged
    while (true) {
      const PathSegment& seg = segs[i];
      if (t - elapsed <= seg.duration_s) {
        return with_bank_rate(advance(s, seg, t - elapsed), prev_rate, seg, next_turn_rate(i), t - elapsed,
                              seg.duration_s);
      }
      s = advance(s, seg, seg.duration_s);
      elapsed += seg.duration_s;
      prev_rate = seg.turn_rate_radps;
      ++i;
      if (i == segs.size()) {
        if (!spec_.repeat) {
          // Past the last finite segment: continue straight at constant speed.
          return with_bank_rate(advance(s, straight_on, t - elapsed), prev_rate, straight_on, 0.0, t - elapsed,
                                straight_on.duration_s);
        }
        i = 0;
      }
    }
  }

  /// Turn rate of the segment after segment i (straight on after the last one unless repeating).
  double next_turn_rate(std::size_t i) const {
    if (i + 1 < spec_.segments.size()) return spec_.segments[i + 1].turn_rate_radps;
    return spec_.repeat ? spec_.segments.front().turn_rate_radps : 0.0;
  }

  PlanarState with_bank_rate(PlanarState s, double prev_rate, const PathSegment& seg, double next_rate,
                             double time_in_segment, double duration) const {
    s.bank_turn_rate_radps =
        blended_turn_rate(prev_rate, seg.turn_rate_radps, next_rate, time_in_segment, duration, spec_.roll_reversal_s);
    return s;
  }

  /// Tangent-frame (start NED) position, velocity, acceleration.
  void tangent(double t, Eigen::Vector3d& p, Eigen::Vector3d& v, Eigen::Vector3d& a, PlanarState& ps) const {
    ps = planar(t);
    const Eigen::Vector2d u(std::cos(ps.course_rad), std::sin(ps.course_rad));
    const Eigen::Vector2d n(-std::sin(ps.course_rad), std::cos(ps.course_rad));  // right of the course
    p << ps.p_m.x(), ps.p_m.y(), -spec_.climb_mps * t;
    v << ps.speed_mps * u.x(), ps.speed_mps * u.y(), -spec_.climb_mps;
    const Eigen::Vector2d a_h = ps.accel_mps2 * u + ps.speed_mps * ps.turn_rate_radps * n;
    a << a_h.x(), a_h.y(), 0.0;
  }

  Eigen::Quaterniond attitude_in_tangent(double t, const PlanarState& ps) const {
    EulerAngles e;
    e.yaw_rad = ps.course_rad;
    e.pitch_rad = std::atan2(spec_.climb_mps, std::abs(ps.speed_mps));
    if (spec_.bank_in_turns) e.roll_rad = std::atan(ps.speed_mps * ps.bank_turn_rate_radps / kStandardGravity);
    if (spec_.wingrock_amplitude_rad != 0.0) {
      e.roll_rad += spec_.wingrock_amplitude_rad * std::sin(2.0 * kPi * t / spec_.wingrock_period_s);
    }
    return quaternion_from_euler(e);
  }

  Eigen::Quaterniond attitude(double t) const {
    Eigen::Vector3d p, v, a;
    PlanarState ps;
    tangent(t, p, v, a, ps);
    const wgs84::Llh llh = wgs84::ecef_to_llh(r0_ecef_ + C_t_e_ * p);
    const Eigen::Matrix3d C_t_n = C_e_n(llh.lat_rad, llh.lon_rad) * C_t_e_;
    return Eigen::Quaterniond(C_t_n) * attitude_in_tangent(t, ps);
  }

  TrajectoryState kinematics(double t) const {
    Eigen::Vector3d p, v, a;
    PlanarState ps;
    tangent(t, p, v, a, ps);
    TrajectoryState s;
    s.t_s = t;
    s.r_ecef_m = r0_ecef_ + C_t_e_ * p;
    s.v_ecef_mps = C_t_e_ * v;
    s.a_ecef_mps2 = C_t_e_ * a;
    const wgs84::Llh llh = wgs84::ecef_to_llh(s.r_ecef_m);
    const Eigen::Matrix3d C_en = C_e_n(llh.lat_rad, llh.lon_rad);
    s.v_ned_mps = C_en * s.v_ecef_mps;
    // d(v_ned)/dt = C_e_n a_ecef + dC_e_n/dt v_ecef, and dC_e_n/dt = -[w_en_n x] C_e_n.
    s.a_ned_mps2 = C_en * s.a_ecef_mps2 - transport_rate_ned_radps(llh, s.v_ned_mps).cross(s.v_ned_mps);
    s.q_b_n = Eigen::Quaterniond(C_en * C_t_e_) * attitude_in_tangent(t, ps);
    s.q_b_n.normalize();
    return s;
  }

  PathSpec spec_;
  Eigen::Vector3d r0_ecef_;
  Eigen::Matrix3d C_t_e_;
};

PathSpec circle(const std::string& name, double speed, double turn_rate, bool aircraft) {
  PathSpec p;
  p.name = name;
  p.speed_mps = speed;
  p.segments = {PathSegment{std::numeric_limits<double>::infinity(), 0.0, turn_rate}};
  p.bank_in_turns = aircraft;
  return p;
}

PathSpec s_shape(const std::string& name, double speed, double turn_rate, bool aircraft) {
  PathSpec p = circle(name, speed, turn_rate, aircraft);
  const double half = kPi / turn_rate;
  p.segments = {PathSegment{half, 0.0, turn_rate}, PathSegment{half, 0.0, -turn_rate}};
  p.repeat = true;
  return p;
}

PathSpec preset_spec(const std::string& name) {
  const double land_v = 10.0 * kKmh, air_v = 500.0 * kKmh;
  const double land_w = land_v / 87.27, air_w = kPi / 100.0;
  if (name == "static") return circle(name, 0.0, 0.0, false);
  if (name == "land-straight") return circle(name, land_v, 0.0, false);
  if (name == "land-accel") {
    PathSpec p = circle(name, 0.0, 0.0, false);
    p.segments = {PathSegment{std::numeric_limits<double>::infinity(), 0.1, 0.0}};
    return p;
  }
  if (name == "land-circle") return circle(name, land_v, land_w, false);
  if (name == "land-s") return s_shape(name, land_v, land_w, false);
  for (int scale : {1, 2}) {
    const std::string suffix = scale == 2 ? "-x2" : "";
    if (name == "air-circle" + suffix) return circle(name, air_v, scale * air_w, true);
    if (name == "air-s" + suffix) return s_shape(name, air_v, scale * air_w, true);
    if (name == "air-spiral" + suffix) {
      PathSpec p = circle(name, 4422.0 * kPi / 50.0, scale * kPi / 50.0, true);
      p.climb_mps = 0.2;
      return p;
    }
    if (name == "air-wingrock" + suffix) {
      PathSpec p = circle(name, air_v, 0.0, true);
      p.wingrock_amplitude_rad = scale * 20.0 * kPi / 180.0;
      return p;
    }
  }
  std::string names;
  for (const auto& n : preset_trajectory_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown trajectory preset '" + name + "' (expected one of: " + names + ")");
}

}  // namespace

std::unique_ptr<Trajectory> make_path_trajectory(const PathSpec& spec) {
  return std::make_unique<PathTrajectory>(spec);
}

std::unique_ptr<Trajectory> make_preset_trajectory(const std::string& name, const wgs84::Llh& start, double heading_rad,
                                                   double duration_s) {
  PathSpec spec = preset_spec(name);
  spec.start = start;
  spec.heading_rad = heading_rad;
  spec.duration_s = duration_s;
  return make_path_trajectory(spec);
}

std::vector<std::string> preset_trajectory_names() {
  return {"static",     "land-straight", "land-accel",    "land-circle", "land-s",        "air-circle",     "air-s",
          "air-spiral", "air-wingrock",  "air-circle-x2", "air-s-x2",    "air-spiral-x2", "air-wingrock-x2"};
}

}  // namespace deepnav
