#include "receiver/observations/solution_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "ins/frames.hpp"

namespace deepnav {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kMatch_s = 0.01;

double number(const std::string& path, int line, const std::string& text, const char* field) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw std::runtime_error(fmt::format("{}:{}: {}: '{}' is not a number", path, line, field, text));
  return v;
}

}  // namespace

std::vector<SolutionPoint> read_rtklib_pos(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open solution file '" + path + "'");
  std::vector<SolutionPoint> out;
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    if (raw.empty() || raw[0] == '%' || raw.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream ss(raw);
    std::vector<std::string> f;
    for (std::string s; ss >> s;) f.push_back(s);
    if (f.size() < 5)
      throw std::runtime_error(
          fmt::format("{}:{}: expected time, latitude, longitude, height, Q; found {} fields", path, line, f.size()));
    SolutionPoint p;
    if (f[0].find('/') != std::string::npos) {
      CalendarTime c;
      if (std::sscanf(f[0].c_str(), "%d/%d/%d", &c.year, &c.month, &c.day) != 3 || c.month < 1 || c.month > 12 ||
          c.day < 1 || c.day > 31)
        throw std::runtime_error(fmt::format("{}:{}: date '{}' is not yyyy/mm/dd", path, line, f[0]));
      if (std::sscanf(f[1].c_str(), "%d:%d:%lf", &c.hour, &c.minute, &c.second) != 3 || c.hour < 0 || c.hour > 23 ||
          c.minute < 0 || c.minute > 59 || c.second < 0 || c.second >= 61)
        throw std::runtime_error(fmt::format("{}:{}: time '{}' is not hh:mm:ss.sss", path, line, f[1]));
      p.t = gps_time_from_calendar(c);
    } else {
      const double week = number(path, line, f[0], "GPS week");
      p.t = GpsTime::normalized(static_cast<int>(week), number(path, line, f[1], "seconds of week"));
    }
    const double lat = number(path, line, f[2], "latitude");
    const double lon = number(path, line, f[3], "longitude");
    if (std::abs(lat) > 90.0 || std::abs(lon) > 360.0)
      throw std::runtime_error(
          fmt::format("{}:{}: latitude/longitude {} {} out of range (is the file in ECEF? write "
                      "latitude/longitude/height)",
                      path, line, f[2], f[3]));
    p.llh = {lat * kDegToRad, lon * kDegToRad, number(path, line, f[4], "height")};
    if (f.size() > 5) p.quality = static_cast<int>(number(path, line, f[5], "Q"));
    if (f.size() > 6) p.satellites = static_cast<int>(number(path, line, f[6], "ns"));
    out.push_back(p);
  }
  if (out.empty()) throw std::runtime_error("solution file '" + path + "' holds no solutions");
  return out;
}

ReferenceErrors reference_errors(const std::vector<SolutionPoint>& solution,
                                 const std::vector<SolutionPoint>& reference) {
  ReferenceErrors r;
  if (reference.empty()) return r;
  const wgs84::Llh origin = reference.front().llh;
  std::vector<Eigen::Vector3d> errors;
  for (const SolutionPoint& s : solution) {
    const auto it =
        std::lower_bound(reference.begin(), reference.end(), s.t,
                         [](const SolutionPoint& p, const GpsTime& t) { return p.t.seconds_since(t) < -kMatch_s; });
    if (it == reference.end() || std::abs(it->t.seconds_since(s.t)) > kMatch_s) continue;
    const Eigen::Vector3d d_ned = ecef_to_ned_vector(origin, wgs84::llh_to_ecef(s.llh) - wgs84::llh_to_ecef(it->llh));
    errors.emplace_back(d_ned.y(), d_ned.x(), -d_ned.z());
    r.matched.push_back(s.t);
  }
  r.epochs = static_cast<int>(errors.size());
  if (errors.empty()) return r;
  for (const auto& e : errors) r.mean_offset_enu_m += e;
  r.mean_offset_enu_m /= static_cast<double>(errors.size());
  std::vector<double> scatter_h;
  double sh = 0, sv = 0, s3 = 0, ch = 0, cv = 0;
  for (const auto& e : errors) {
    sh += e.head<2>().squaredNorm();
    sv += e.z() * e.z();
    s3 += e.squaredNorm();
    const Eigen::Vector3d c = e - r.mean_offset_enu_m;
    ch += c.head<2>().squaredNorm();
    cv += c.z() * c.z();
    scatter_h.push_back(c.head<2>().norm());
    r.scatter_max_3d_m = std::max(r.scatter_max_3d_m, c.norm());
  }
  const double n = static_cast<double>(errors.size());
  r.rms_horizontal_m = std::sqrt(sh / n);
  r.rms_vertical_m = std::sqrt(sv / n);
  r.rms_3d_m = std::sqrt(s3 / n);
  r.scatter_rms_horizontal_m = std::sqrt(ch / n);
  r.scatter_rms_vertical_m = std::sqrt(cv / n);
  std::sort(scatter_h.begin(), scatter_h.end());
  r.scatter_max_horizontal_m = scatter_h.back();
  r.scatter_p95_horizontal_m = scatter_h[std::min(scatter_h.size() - 1, static_cast<std::size_t>(0.95 * n))];
  return r;
}

nlohmann::json ReferenceErrors::json() const {
  // No epoch scored: no statistic, rather than a perfect score of zeros.
  const auto value = [&](double v) { return epochs > 0 ? nlohmann::json(std::round(v * 1000.0) / 1000.0) : nullptr; };
  return {{"epochs", epochs},
          {"mean_offset_enu_m", epochs > 0
                                    ? nlohmann::json::array({value(mean_offset_enu_m.x()), value(mean_offset_enu_m.y()),
                                                             value(mean_offset_enu_m.z())})
                                    : nlohmann::json(nullptr)},
          {"rms_horizontal_m", value(rms_horizontal_m)},
          {"rms_vertical_m", value(rms_vertical_m)},
          {"rms_3d_m", value(rms_3d_m)},
          {"about_mean_offset",
           {{"rms_horizontal_m", value(scatter_rms_horizontal_m)},
            {"rms_vertical_m", value(scatter_rms_vertical_m)},
            {"p95_horizontal_m", value(scatter_p95_horizontal_m)},
            {"max_horizontal_m", value(scatter_max_horizontal_m)},
            {"max_3d_m", value(scatter_max_3d_m)}}}};
}

}  // namespace deepnav
