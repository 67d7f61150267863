#include "receiver/products/truth_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "ins/input_file.hpp"

namespace deepnav {
namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) {
    const auto b = field.find_first_not_of(" \t");
    const auto e = field.find_last_not_of(" \t");
    out.push_back(b == std::string::npos ? std::string() : field.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();  // a trailing empty field
  return out;
}

/// The whole field as a finite number, else nullopt ("123.4junk", "nan", "inf", "").
std::optional<double> finite_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

TruthFile::TruthFile(const std::string& path) {
  check_input_file(path, "truth file", kMaxTextInputBytes);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open truth file '" + path + "'");
  read(in, path);
}

TruthFile::TruthFile(std::istream& in, const std::string& name) { read(in, name); }

void TruthFile::read(std::istream& in, const std::string& path) {
  const auto fail = [&](int line, const std::string& what) -> void {
    throw std::runtime_error(fmt::format("{}:{}: {}", path, line, what));
  };
  std::string line;
  if (!std::getline(in, line)) fail(1, "empty truth file");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> header = split_fields(line);
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i].empty()) fail(1, fmt::format("column {} of the header has no name", i + 1));
    if (const auto [it, fresh] = col.emplace(header[i], i); !fresh)
      fail(1, fmt::format("column name '{}' appears twice (columns {} and {})", header[i], it->second + 1, i + 1));
  }
  for (const char* need : {"t_s", "x_ecef_m", "y_ecef_m", "z_ecef_m", "vx_ecef_mps", "vy_ecef_mps", "vz_ecef_mps"}) {
    if (!col.count(need)) fail(1, std::string("truth header lacks column '") + need + "'");
  }
  const bool has_sow = col.count("gps_sow") && col.count("clock_bias_s");
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() != header.size())
      fail(line_no, fmt::format("expected {} columns (as the header), got {}", header.size(), fields.size()));
    const auto value = [&](const char* name) {
      const std::size_t i = col.at(name);
      const auto v = finite_number(fields[i]);
      if (!v) fail(line_no, fmt::format("column '{}': '{}' is not a finite number", name, fields[i]));
      return *v;
    };
    TruthSample t;
    t.t_s = value("t_s");
    t.r_ecef_m = {value("x_ecef_m"), value("y_ecef_m"), value("z_ecef_m")};
    t.v_ecef_mps = {value("vx_ecef_mps"), value("vy_ecef_mps"), value("vz_ecef_mps")};
    if (has_sow) t.true_sow = value("gps_sow") - value("clock_bias_s");
    if (!rows_.empty() && !(t.t_s > rows_.back().t_s))
      fail(line_no, fmt::format("t_s {} does not increase (previous row: {})", t.t_s, rows_.back().t_s));
    rows_.push_back(t);
  }
  if (rows_.size() < 2) throw std::runtime_error(path + ": fewer than 2 truth rows");
}

std::optional<TruthSample> TruthFile::at(double t) const {
  if (t < rows_.front().t_s || t > rows_.back().t_s) return std::nullopt;
  auto hi = std::lower_bound(rows_.begin(), rows_.end(), t, [](const TruthSample& r, double x) { return r.t_s < x; });
  if (hi == rows_.begin()) return *hi;
  const auto lo = hi - 1;
  const double w = (t - lo->t_s) / (hi->t_s - lo->t_s);
  TruthSample out;
  out.t_s = t;
  out.r_ecef_m = (1 - w) * lo->r_ecef_m + w * hi->r_ecef_m;
  out.v_ecef_mps = (1 - w) * lo->v_ecef_mps + w * hi->v_ecef_mps;
  if (lo->true_sow && hi->true_sow) out.true_sow = *lo->true_sow + w * (*hi->true_sow - *lo->true_sow);
  return out;
}

}  // namespace deepnav
