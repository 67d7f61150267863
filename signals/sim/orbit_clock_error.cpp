#include "signals/sim/orbit_clock_error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "signals/sim/error_seed.hpp"

namespace deepnav {
namespace {

constexpr double kGridMargin_s = 60.0;  // receiver clock bias and drift move true time off the nominal span
constexpr int kPrns = 32;
constexpr int kGalileoPrns = 50;
/// Galileo satellites draw from generators of their own: PRN key 100 + SVID.
constexpr int kGalileoKeyOffset = 100;

/// Index of a satellite's series: GPS PRNs first, then Galileo SVIDs; -1 for none.
int series_index(const SatelliteId& id) {
  if (id.system == GnssSystem::gps) return id.prn >= 1 && id.prn <= kPrns ? id.prn - 1 : -1;
  return id.prn >= 1 && id.prn <= kGalileoPrns ? kPrns + id.prn - 1 : -1;
}

}  // namespace

double OrbitClockErrorSpec::global_average_sisre_m() const {
  return std::sqrt(radial_m * radial_m + clock_m * clock_m + (along_m * along_m + cross_m * cross_m) / 49.0);
}

OrbitClockError::OrbitClockError(const OrbitClockErrorSpec& spec, std::uint64_t seed, const GpsTime& start,
                                 double duration_s)
    : spec_(spec), grid_start_(start.plus_seconds(-kGridMargin_s)) {
  if (!spec_.any()) return;
  nodes_ = static_cast<std::size_t>(std::ceil((duration_s + 2.0 * kGridMargin_s) / kStep_s)) + 2;
  const double phi = std::exp(-kStep_s / spec_.correlation_time_s);
  const double drive = std::sqrt(1.0 - phi * phi);
  const std::array<double, 4> sigma{spec_.radial_m, spec_.along_m, spec_.cross_m, spec_.clock_m};
  series_.resize(kPrns + kGalileoPrns);
  for (int index = 0; index < kPrns + kGalileoPrns; ++index) {
    const int key = index < kPrns ? index + 1 : kGalileoKeyOffset + index - kPrns + 1;
    for (std::size_t c = 0; c < 4; ++c) {
      // One generator per satellite and component: a satellite's errors do not depend on
      // the others, and a longer run repeats a shorter one over their common span.
      auto rng = error_rng(seed, ErrorSource::orbit_clock, key, static_cast<int>(c));
      std::normal_distribution<double> normal(0.0, 1.0);
      std::vector<double>& x = series_[static_cast<std::size_t>(index)][c];
      x.resize(nodes_);
      double v = sigma[c] * normal(rng);  // stationary from the first node
      for (std::size_t i = 0; i < nodes_; ++i) {
        x[i] = v;
        v = phi * v + sigma[c] * drive * normal(rng);
      }
    }
  }
}

OrbitClockErrorSample OrbitClockError::at(int prn, const GpsTime& t) const {
  return at(SatelliteId{GnssSystem::gps, prn}, t);
}

OrbitClockErrorSample OrbitClockError::at(const SatelliteId& id, const GpsTime& t) const {
  OrbitClockErrorSample s;
  const int index = series_index(id);
  if (!active() || index < 0) return s;
  const double x = std::clamp(t.seconds_since(grid_start_) / kStep_s, 0.0, static_cast<double>(nodes_ - 1));
  const auto i = std::min(static_cast<std::size_t>(x), nodes_ - 2);
  const double u = x - static_cast<double>(i);
  // Catmull-Rom through nodes i-1..i+2 (ends repeated): continuous value and rate.
  const std::size_t i0 = i == 0 ? 0 : i - 1, i3 = std::min(i + 2, nodes_ - 1);
  auto eval = [&](const std::vector<double>& p) {
    const double p0 = p[i0], p1 = p[i], p2 = p[i + 1], p3 = p[i3];
    return p1 + 0.5 * u * (p2 - p0 + u * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + u * (3.0 * (p1 - p2) + p3 - p0)));
  };
  const auto& sat = series_[static_cast<std::size_t>(index)];
  s.rac_m = Eigen::Vector3d(eval(sat[0]), eval(sat[1]), eval(sat[2]));
  s.clock_m = eval(sat[3]);
  return s;
}

Eigen::Matrix3d rac_to_ecef(const Eigen::Vector3d& r_ecef_m, const Eigen::Vector3d& v_inertial_ecef_mps) {
  const Eigen::Vector3d radial = r_ecef_m.normalized();
  const Eigen::Vector3d cross = r_ecef_m.cross(v_inertial_ecef_mps).normalized();
  const Eigen::Vector3d along = cross.cross(radial);
  Eigen::Matrix3d m;
  m.col(0) = radial;
  m.col(1) = along;
  m.col(2) = cross;
  return m;
}

}  // namespace deepnav
