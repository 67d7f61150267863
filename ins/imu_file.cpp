#include "ins/imu_file.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "ins/input_file.hpp"
#include "ins/output_file.hpp"

namespace deepnav {
namespace {

constexpr std::array<std::string_view, 7> kIncrementColumns = {
    "t_s", "dtheta_x_rad", "dtheta_y_rad", "dtheta_z_rad", "dv_x_mps", "dv_y_mps", "dv_z_mps"};
constexpr std::array<std::string_view, 7> kRateColumns = {"t_s",     "wx_radps", "wy_radps", "wz_radps",
                                                          "fx_mps2", "fy_mps2",  "fz_mps2"};
constexpr std::string_view kRateKey = "sample_rate_hz=";

std::string join(const std::array<std::string_view, 7>& columns) {
  std::string out;
  for (const auto c : columns) {
    if (!out.empty()) out += ',';
    out += c;
  }
  return out;
}

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& what) {
  throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

ImuFileForm parse_header(const std::string& path, std::size_t line_no, std::string_view line) {
  std::vector<std::string_view> names = split(line);
  for (auto& n : names) n = trim(n);
  for (const auto& [columns, form] :
       {std::pair{kIncrementColumns, ImuFileForm::kIncrements}, std::pair{kRateColumns, ImuFileForm::kRates}}) {
    if (names.size() == columns.size() && std::equal(names.begin(), names.end(), columns.begin())) return form;
  }
  fail(path, line_no,
       "unrecognised IMU header '" + std::string(line) + "'; expected '" + join(kIncrementColumns) + "' or '" +
           join(kRateColumns) + "' (names and units exactly)");
}

double parse_value(const std::string& path, std::size_t line_no, std::string_view field, std::string_view column) {
  field = trim(field);
  double value = 0.0;
  const auto result = std::from_chars(field.data(), field.data() + field.size(), value);
  if (result.ec != std::errc() || result.ptr != field.data() + field.size()) {
    fail(path, line_no, "column '" + std::string(column) + "': '" + std::string(field) + "' is not a number");
  }
  if (!std::isfinite(value)) {
    fail(path, line_no, "column '" + std::string(column) + "': value is " + std::string(field) + " (must be finite)");
  }
  return value;
}

struct Row {
  std::size_t line;
  double t_s;
  Eigen::Vector3d a, b;
};

double median_interval(const std::vector<Row>& rows) {
  std::vector<double> dts;
  for (std::size_t i = 1; i < rows.size(); ++i) dts.push_back(rows[i].t_s - rows[i - 1].t_s);
  if (dts.empty()) return 0.0;
  std::nth_element(dts.begin(), dts.begin() + static_cast<std::ptrdiff_t>(dts.size() / 2), dts.end());
  return dts[dts.size() / 2];
}

/// A row whose rate or specific force (over `dt` for increments) no sensor could measure.
void check_sensor_range(const std::string& path, const Row& row, ImuFileForm form, double dt) {
  const bool rates = form == ImuFileForm::kRates;
  const auto& columns = rates ? kRateColumns : kIncrementColumns;
  if (!rates && !(dt > 0.0)) return;  // a single sample: no interval to divide by
  for (int i = 0; i < 6; ++i) {
    const double value = i < 3 ? row.a[i] : row.b[i - 3];
    const double per_second = rates ? value : value / dt;
    const double limit = i < 3 ? kMaxImuRate_radps : kMaxImuSpecificForce_mps2;
    if (std::abs(per_second) <= limit) continue;
    char text[200];
    if (rates)
      std::snprintf(text, sizeof text, "%g is beyond any %s's range (%g %s)", value, i < 3 ? "gyro" : "accelerometer",
                    limit, i < 3 ? "rad/s, 10000 deg/s" : "m/s^2, about 1000 g");
    else
      std::snprintf(text, sizeof text, "%g over %g s is %s of %g %s, beyond any %s's range (%g)", value, dt,
                    i < 3 ? "an angular rate" : "a specific force", per_second, i < 3 ? "rad/s" : "m/s^2",
                    i < 3 ? "gyro" : "accelerometer", limit);
    fail(path, row.line, "column '" + std::string(columns[static_cast<std::size_t>(1 + i)]) + "': " + text);
  }
}

}  // namespace

void write_imu_csv(const std::string& path, const std::vector<ImuSample>& samples, ImuFileForm form,
                   double sample_rate_hz) {
  if (!(sample_rate_hz > 0.0)) throw std::invalid_argument("write_imu_csv: sample_rate_hz must be > 0");
  const bool rates = form == ImuFileForm::kRates;
  std::string text = "# deepnav IMU data, ";
  text += rates ? "rates held over the interval ending at t_s\n" : "increments over the interval ending at t_s\n";
  text += "# ";
  text += kRateKey;
  append_number(text, sample_rate_hz);
  text += '\n';
  text += join(rates ? kRateColumns : kIncrementColumns);
  text += '\n';
  double t_previous = samples.empty() ? 0.0 : samples.front().t_s - 1.0 / sample_rate_hz;
  for (const auto& s : samples) {
    const double scale = rates ? 1.0 / (s.t_s - t_previous) : 1.0;
    t_previous = s.t_s;
    append_number(text, s.t_s);
    for (int i = 0; i < 3; ++i) text += ',', append_number(text, s.dtheta_b_rad[i] * scale);
    for (int i = 0; i < 3; ++i) text += ',', append_number(text, s.dv_b_mps[i] * scale);
    text += '\n';
  }

  OutputFile file(path);
  file.write(text);
  file.commit();
}

ImuLog read_imu_csv(const std::string& path) {
  check_input_file(path, "IMU file", kMaxTextInputBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open IMU file '" + path + "'");
  return read_imu_csv(in, path);
}

ImuLog read_imu_csv(std::istream& in, const std::string& path) {
  ImuLog log;
  log.source = path;
  double declared_rate_hz = 0.0;
  bool have_header = false;
  std::vector<Row> rows;
  std::string raw;
  std::size_t line_no = 0;
  while (std::getline(in, raw)) {
    ++line_no;
    const std::string_view line = trim(raw);
    if (!have_header) {
      if (line.empty()) continue;
      if (line.front() == '#') {
        const auto at = line.find(kRateKey);
        if (at != std::string_view::npos) {
          declared_rate_hz = parse_value(path, line_no, line.substr(at + kRateKey.size()), "sample_rate_hz");
          if (declared_rate_hz <= 0.0) fail(path, line_no, "sample_rate_hz must be > 0");
        }
        continue;
      }
      log.form = parse_header(path, line_no, line);
      have_header = true;
      continue;
    }
    if (line.empty()) fail(path, line_no, "empty line inside the data (expected 7 comma-separated values)");
    const auto fields = split(line);
    if (fields.size() != 7) {
      fail(path, line_no, "expected 7 comma-separated values, found " + std::to_string(fields.size()));
    }
    const auto& columns = log.form == ImuFileForm::kRates ? kRateColumns : kIncrementColumns;
    Row row{line_no, parse_value(path, line_no, fields[0], columns[0]), {}, {}};
    for (int i = 0; i < 3; ++i) row.a[i] = parse_value(path, line_no, fields[1 + i], columns[1 + i]);
    for (int i = 0; i < 3; ++i) row.b[i] = parse_value(path, line_no, fields[4 + i], columns[4 + i]);
    if (!rows.empty() && row.t_s <= rows.back().t_s) {
      fail(path, line_no,
           std::string(row.t_s == rows.back().t_s ? "duplicate" : "non-monotonic") +
               " timestamp t_s = " + std::string(trim(fields[0])) + " after line " + std::to_string(rows.back().line) +
               " (timestamps must increase)");
    }
    rows.push_back(row);
  }
  if (!have_header) fail(path, line_no, "no header line (expected '" + join(kIncrementColumns) + "')");

  log.nominal_interval_s = declared_rate_hz > 0.0 ? 1.0 / declared_rate_hz : median_interval(rows);
  log.samples.reserve(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    double dt = log.nominal_interval_s;
    if (i > 0) {
      const double interval = rows[i].t_s - rows[i - 1].t_s;
      if (interval > 1.5 * log.nominal_interval_s) {
        log.gaps.push_back({rows[i].line, rows[i - 1].t_s, rows[i].t_s});
      } else {
        dt = interval;
      }
    }
    const double scale = log.form == ImuFileForm::kRates ? dt : 1.0;
    check_sensor_range(path, rows[i], log.form, dt);
    log.samples.push_back({rows[i].t_s, rows[i].a * scale, rows[i].b * scale});
  }
  return log;
}

}  // namespace deepnav
