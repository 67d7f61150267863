#include "ins/imu_log_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "ins/imu_model.hpp"
#include "ins/rotations.hpp"

namespace deepnav {
namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

/// Fields split at commas (csv), or at commas, blanks and tabs (kf-gins).
std::vector<std::string_view> split(std::string_view line, bool blanks_too) {
  std::vector<std::string_view> out;
  if (!blanks_too) {
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      out.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
      if (comma == std::string_view::npos) return out;
      start = comma + 1;
    }
  }
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && !(line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r')) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::optional<double> to_number(std::string_view field) {
  double v = 0.0;
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  const auto r = std::from_chars(field.data(), field.data() + field.size(), v);
  if (r.ec != std::errc() || r.ptr != field.data() + field.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// Where each quantity is in a row: time, accelerometer x y z, gyro x y z.
struct Layout {
  int time = -1;
  std::array<int, 3> accel{-1, -1, -1}, gyro{-1, -1, -1};
  int fields = 0;  ///< columns a row must have (at least)
  std::vector<std::string> names;
};

Layout parse_columns(const std::string& spec, const std::string& path) {
  Layout l;
  std::stringstream ss(spec);
  std::string name;
  int index = 0;
  while (std::getline(ss, name, ',')) {
    const std::string n(trim(name));
    l.names.push_back(n);
    const auto set = [&](int& slot) {
      if (slot >= 0) throw std::runtime_error(path + ": IMU column map '" + spec + "': '" + n + "' named twice");
      slot = index;
    };
    if (n == "t") set(l.time);
    else if (n == "ax" || n == "ay" || n == "az") set(l.accel[static_cast<std::size_t>(n[1] - 'x')]);
    else if (n == "gx" || n == "gy" || n == "gz") set(l.gyro[static_cast<std::size_t>(n[1] - 'x')]);
    else if (n != "-")
      throw std::runtime_error(path + ": IMU column map '" + spec + "': column " + std::to_string(index + 1) + " is '" +
                               n + "'; each column is one of t, ax, ay, az, gx, gy, gz or - (ignored)");
    ++index;
  }
  l.fields = index;
  std::string missing;
  if (l.time < 0) missing += " t";
  for (int i = 0; i < 3; ++i) {
    if (l.accel[static_cast<std::size_t>(i)] < 0) missing += std::string(" a") + "xyz"[i];
    if (l.gyro[static_cast<std::size_t>(i)] < 0) missing += std::string(" g") + "xyz"[i];
  }
  if (!missing.empty())
    throw std::runtime_error(path + ": IMU column map '" + spec + "' lacks" + missing +
                             " (it names t, ax, ay, az, gx, gy, gz)");
  return l;
}

/// Multipliers to SI (m/s^2 or m/s; rad/s or rad) for the csv units.
double accel_scale(const std::string& unit, ImuQuantity q, const std::string& path) {
  if (unit == "g" || unit == "g*s") return imu_units::kStandardGravity_mps2;
  if ((q == ImuQuantity::rates && (unit == "m/s^2" || unit == "m/s2" || unit == "mps2")) ||
      (q == ImuQuantity::increments && (unit == "m/s" || unit == "mps")))
    return 1.0;
  throw std::runtime_error(path + ": accelerometer unit '" + unit + "' is not one of " +
                           (q == ImuQuantity::rates ? "g, m/s^2" : "g*s, m/s") + " (for " +
                           (q == ImuQuantity::rates ? "rates" : "increments") + ")");
}

double gyro_scale(const std::string& unit, ImuQuantity q, const std::string& path) {
  if ((q == ImuQuantity::rates && unit == "deg/s") || (q == ImuQuantity::increments && unit == "deg"))
    return imu_units::kDegToRad;
  if ((q == ImuQuantity::rates && unit == "rad/s") || (q == ImuQuantity::increments && unit == "rad")) return 1.0;
  throw std::runtime_error(path + ": gyro unit '" + unit + "' is not one of " +
                           (q == ImuQuantity::rates ? "deg/s, rad/s" : "deg, rad") + " (for " +
                           (q == ImuQuantity::rates ? "rates" : "increments") + ")");
}

struct Row {
  int line;
  double t;
  Eigen::Vector3d a, g;  // SI, rates or increments as the file holds them
};

ImuLogRead from_deepnav_csv(const std::string& path, const ImuLogOptions& o) {
  ImuLogRead r;
  r.log = read_imu_csv(path);
  for (ImuSample& s : r.log.samples) s.t_s = o.time_offset_s + o.time_scale * s.t_s;
  for (ImuGap& g : r.log.gaps) {
    g.t_before_s = o.time_offset_s + o.time_scale * g.t_before_s;
    g.t_after_s = o.time_offset_s + o.time_scale * g.t_after_s;
  }
  r.log.nominal_interval_s *= o.time_scale;
  r.report.format = "deepnav";
  r.report.time_scale = o.time_scale;
  r.report.time_offset_s = o.time_offset_s;
  r.report.rows = r.report.samples = static_cast<int>(r.log.samples.size());
  r.report.gaps = r.log.gaps;
  r.report.nominal_interval_s = r.log.nominal_interval_s;
  return r;
}

/// The kept rows as increments: a rate held over the interval ending at its time; an
/// interval over gap_factor nominal ones is a gap, its next sample one nominal interval.
void integrate_rows(const std::vector<Row>& rows, ImuQuantity quantity, const ImuLogOptions& o, ImuLogRead& result) {
  ImuLogReport& rep = result.report;
  const double span = rows.back().t - rows.front().t;
  result.log.nominal_interval_s =
      o.nominal_rate_hz ? 1.0 / *o.nominal_rate_hz : span / static_cast<double>(rows.size() - 1);
  result.log.form = quantity == ImuQuantity::rates ? ImuFileForm::kRates : ImuFileForm::kIncrements;
  const double nominal = result.log.nominal_interval_s;
  rep.min_interval_s = 1e300;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    double dt = nominal;
    if (i > 0) {
      const double interval = rows[i].t - rows[i - 1].t;
      rep.min_interval_s = std::min(rep.min_interval_s, interval);
      rep.max_interval_s = std::max(rep.max_interval_s, interval);
      if (interval > o.gap_factor * nominal) {
        result.log.gaps.push_back({static_cast<std::size_t>(rows[i].line), rows[i - 1].t, rows[i].t});
      } else {
        dt = interval;
      }
    }
    const double scale = quantity == ImuQuantity::rates ? dt : 1.0;
    result.log.samples.push_back({rows[i].t, rows[i].g * scale, rows[i].a * scale});
  }
  rep.mean_interval_s = span / static_cast<double>(rows.size() - 1);
  rep.nominal_interval_s = nominal;
  rep.gaps = result.log.gaps;
}

/// The report's figures of the log as read, whatever its format.
void finish_report(ImuLogRead& result) {
  ImuLogReport& rep = result.report;
  if (result.log.samples.empty()) fail(result.log.source, rep.lines, "no IMU samples in the file");
  rep.samples = static_cast<int>(result.log.samples.size());
  rep.first_t_s = result.log.samples.front().t_s;
  rep.last_t_s = result.log.samples.back().t_s;
}

void check_time_mapping(const std::string& path, const ImuLogOptions& o) {
  if (!(o.time_scale > 0.0) || !std::isfinite(o.time_scale) || !std::isfinite(o.time_offset_s))
    throw std::runtime_error(path + ": IMU time scale must be > 0 and finite, and the offset finite");
}

/// The first line of each kind of row dropped.
struct RowTally {
  int first_duplicate_line = 0, first_repeated_time_line = 0;
};

/// Whether `row` is kept after `prev` (the last row kept); counts what is dropped and the
/// repeated values kept. A time going back is an error naming both lines.
bool keep_row(const Row& row, const Row& prev, const std::string& time_text, ImuLogReport& rep, RowTally& tally,
              const std::string& path) {
  if (row.t < prev.t)
    fail(path, row.line,
         "time " + time_text + " goes back before line " + std::to_string(prev.line) +
             "'s: the log's times must increase (rows out of order, or the logger's clock re-set)");
  const bool same_values = row.a == prev.a && row.g == prev.g;
  if (row.t == prev.t) {
    int& first = same_values ? tally.first_duplicate_line : tally.first_repeated_time_line;
    ++(same_values ? rep.duplicate_rows : rep.repeated_time);
    if (first == 0) first = row.line;
    return false;
  }
  rep.repeated_values += same_values;
  return true;
}

void add_warnings(const std::string& path, const RowTally& tally, ImuLogReport& rep) {
  const auto at = [&](int line) { return path + ":" + std::to_string(line) + ": "; };
  if (rep.duplicate_rows > 0)
    rep.warnings.push_back(at(tally.first_duplicate_line) + std::to_string(rep.duplicate_rows) +
                           " row(s) repeat the row before them, time and values: dropped (written twice)");
  if (rep.repeated_time > 0)
    rep.warnings.push_back(at(tally.first_repeated_time_line) + std::to_string(rep.repeated_time) +
                           " row(s) at the time of the row before them with other values: dropped (two samples "
                           "cannot share a time; is the time column's resolution too coarse?)");
}

/// csv and kf-gins logs.
ImuLogRead read_delimited(std::istream& in, const std::string& path, const ImuLogOptions& o) {
  ImuLogRead result;
  result.log.source = path;
  ImuLogReport& rep = result.report;
  rep.time_scale = o.time_scale;
  rep.time_offset_s = o.time_offset_s;
  const bool kf = o.format == ImuLogFormat::kf_gins;
  const Layout layout = kf ? parse_columns("t,gx,gy,gz,ax,ay,az", path) : parse_columns(o.columns, path);
  const ImuQuantity quantity = kf ? ImuQuantity::increments : o.quantity;
  const double ka = kf ? 1.0 : accel_scale(o.accel_unit, quantity, path);
  const double kg = kf ? 1.0 : gyro_scale(o.gyro_unit, quantity, path);
  rep.format = kf ? "kf-gins" : "csv";

  std::vector<std::string> lines;
  for (std::string s; std::getline(in, s);) lines.push_back(std::move(s));
  rep.lines = static_cast<int>(lines.size());
  // The first and last lines that hold anything (a cut line can only be one of them).
  int first_data = -1, last_data = -1;
  for (int i = 0; i < rep.lines; ++i) {
    const std::string_view t = trim(lines[static_cast<std::size_t>(i)]);
    if (t.empty() || t.front() == '#' || t.front() == '%') continue;
    if (first_data < 0) first_data = i;
    last_data = i;
  }
  std::vector<Row> rows;
  RowTally tally;
  bool seen_data = false;
  for (int i = 0; i < rep.lines; ++i) {
    const int line_no = i + 1;
    const std::string_view text = trim(lines[static_cast<std::size_t>(i)]);
    if (text.empty() || text.front() == '#' || text.front() == '%') {
      ++rep.header_lines;
      continue;
    }
    const std::vector<std::string_view> f = split(text, kf);
    const bool edge = i == first_data || i == last_data;
    if (static_cast<int>(f.size()) < layout.fields) {
      if (edge) {
        ++rep.truncated_lines;
        continue;
      }
      fail(path, line_no,
           "expected " + std::to_string(layout.fields) + " fields (" + o.columns + "), found " +
               std::to_string(f.size()));
    }
    const auto value = [&](int col, const std::string& name) -> std::optional<double> {
      const auto v = to_number(f[static_cast<std::size_t>(col)]);
      if (!v && (seen_data || !edge))
        fail(path, line_no,
             "column " + std::to_string(col + 1) + " (" + name + "): '" +
                 std::string(f[static_cast<std::size_t>(col)]) + "' is not a finite number");
      return v;
    };
    const auto t = value(layout.time, "t");
    if (!t) {  // a header line naming the columns, before any data
      ++rep.header_lines;
      continue;
    }
    Row row{line_no, o.time_offset_s + o.time_scale * *t, {}, {}};
    for (std::size_t k = 0; k < 3; ++k) {
      row.a[static_cast<Eigen::Index>(k)] = ka * *value(layout.accel[k], std::string("a") + "xyz"[k]);
      row.g[static_cast<Eigen::Index>(k)] = kg * *value(layout.gyro[k], std::string("g") + "xyz"[k]);
    }
    seen_data = true;
    ++rep.rows;
    if (rows.empty() ||
        keep_row(row, rows.back(), std::string(f[static_cast<std::size_t>(layout.time)]), rep, tally, path))
      rows.push_back(row);
  }
  if (rows.size() < 2) fail(path, rep.lines, "fewer than two IMU samples in the file");
  integrate_rows(rows, quantity, o, result);
  add_warnings(path, tally, rep);
  return result;
}

}  // namespace

ImuLogFormat parse_imu_log_format(const std::string& name) {
  if (name == "deepnav") return ImuLogFormat::deepnav;
  if (name == "csv") return ImuLogFormat::csv;
  if (name == "kf-gins") return ImuLogFormat::kf_gins;
  throw std::invalid_argument("IMU log format '" + name + "' is not one of deepnav, csv, kf-gins");
}

ImuLogRead read_imu_log(std::istream& in, const std::string& path, const ImuLogOptions& o) {
  if (o.format == ImuLogFormat::deepnav)
    throw std::invalid_argument(path + ": the deepnav IMU format is read from its file (read_imu_csv)");
  check_time_mapping(path, o);
  ImuLogRead result = read_delimited(in, path, o);
  finish_report(result);
  return result;
}

ImuLogRead read_imu_log(const std::string& path, const ImuLogOptions& o) {
  check_time_mapping(path, o);
  ImuLogRead result;
  if (o.format == ImuLogFormat::deepnav) {
    result = from_deepnav_csv(path, o);
  } else {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open IMU log '" + path + "'");
    result = read_delimited(in, path, o);
  }
  finish_report(result);
  return result;
}

Eigen::Matrix3d ImuMounting::C_b_imu() const {
  const double k = imu_units::kDegToRad;
  return dcm_from_euler({rpy_deg.x() * k, rpy_deg.y() * k, rpy_deg.z() * k});
}

void apply_mounting(ImuLog& log, const ImuMounting& mounting) {
  const Eigen::Matrix3d C = mounting.C_b_imu();
  if (C.isIdentity(1e-15)) return;
  for (ImuSample& s : log.samples) {
    s.dtheta_b_rad = C * s.dtheta_b_rad;
    s.dv_b_mps = C * s.dv_b_mps;
  }
}

}  // namespace deepnav
