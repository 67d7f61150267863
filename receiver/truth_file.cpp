#include "receiver/truth_file.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace deepnav {

TruthFile::TruthFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open truth file '" + path + "'");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path + ":1: empty truth file");
  std::map<std::string, std::size_t> col;
  {
    std::stringstream s(line);
    std::string name;
    for (std::size_t i = 0; std::getline(s, name, ','); ++i) col[name] = i;
  }
  for (const char* need : {"t_s", "x_ecef_m", "y_ecef_m", "z_ecef_m", "vx_ecef_mps", "vy_ecef_mps", "vz_ecef_mps"}) {
    if (!col.count(need)) throw std::runtime_error(path + ":1: truth header lacks column '" + need + "'");
  }
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    std::vector<double> v;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, ',')) {
      try {
        v.push_back(std::stod(field));
      } catch (const std::exception&) {
        throw std::runtime_error(path + ":" + std::to_string(line_no) + ": '" + field + "' is not a number");
      }
    }
    if (v.size() < col.size()) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": too few columns");
    TruthSample t;
    t.t_s = v[col["t_s"]];
    t.r_ecef_m = {v[col["x_ecef_m"]], v[col["y_ecef_m"]], v[col["z_ecef_m"]]};
    t.v_ecef_mps = {v[col["vx_ecef_mps"]], v[col["vy_ecef_mps"]], v[col["vz_ecef_mps"]]};
    if (col.count("gps_sow") && col.count("clock_bias_s")) t.true_sow = v[col["gps_sow"]] - v[col["clock_bias_s"]];
    if (!rows_.empty() && !(t.t_s > rows_.back().t_s))
      throw std::runtime_error(path + ":" + std::to_string(line_no) + ": time must increase");
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
