#include "signals/sim/scenario.hpp"
#include "signals/data_path.hpp"

#include "ins/imu_model.hpp"
#include "ins/input_error.hpp"
#include "ins/input_file.hpp"
#include "ins/iso_date_time.hpp"
#include "ins/yaml_checks.hpp"
#include "signals/sim/multipath_presets.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace deepnav {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr std::uintmax_t kMaxScenarioBytes = std::uintmax_t{16} << 20;  // a scenario is a page of YAML

/// A YAML node together with its dotted path, so that every error names the field.
class Field {
 public:
  Field(YAML::Node node, std::string path, const std::string* origin, YAML::Mark parent_mark = YAML::Mark::null_mark())
      : node_(std::move(node)), path_(std::move(path)), origin_(origin), parent_mark_(parent_mark) {}

  [[noreturn]] void fail(const std::string& what) const {
    // A key that is not there has no place of its own: its mapping's is the nearest.
    const auto mark = node_.IsDefined() ? node_.Mark() : parent_mark_;
    const std::string where = mark.line >= 0 ? fmt::format("{}:{}", *origin_, mark.line + 1) : *origin_;
    throw std::invalid_argument(fmt::format("{}: field '{}': {}", where, path_, what));
  }
  bool has(const std::string& key) const { return is_map() && node_[key].IsDefined() && !node_[key].IsNull(); }
  Field operator[](const std::string& key) const {
    if (!node_.IsDefined()) fail("missing required field");
    return Field(node_[key], path_.empty() ? key : path_ + "." + key, origin_, node_.Mark());
  }
  Field at(std::size_t i) const {
    if (!node_.IsDefined()) fail("missing required field");
    return Field(node_[i], fmt::format("{}[{}]", path_, i), origin_, node_.Mark());
  }
  /// A value that must be there (yaml-cpp would otherwise throw "invalid node", naming
  /// neither the file nor the field).
  void require() const {
    if (!node_.IsDefined() || node_.IsNull()) fail("missing required field");
  }
  std::size_t size() const { return node_.IsDefined() ? node_.size() : 0; }
  bool is_map() const { return node_.IsDefined() && node_.IsMap(); }
  bool is_sequence() const { return node_.IsDefined() && node_.IsSequence(); }
  bool is_scalar() const { return node_.IsDefined() && node_.IsScalar(); }

  /// Rejects keys that the schema does not know (typos would otherwise be ignored silently).
  void allow_only(std::initializer_list<const char*> keys) const {
    if (!is_map()) fail(node_.IsDefined() ? "expected a mapping" : "missing required field");
    const std::set<std::string> allowed(keys.begin(), keys.end());
    for (const auto& item : node_) {
      // YAML allows any node as a key ("{[a, b]: 1}"); a field's name is text.
      if (!item.first.IsScalar())
        Field(item.first, path_, origin_).fail("expected field names as keys, got a list, a map or an empty key");
      const auto key = item.first.Scalar();
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& k : allowed) list += (list.empty() ? "" : ", ") + k;
        Field(item.first, path_.empty() ? key : path_ + "." + key, origin_)
            .fail("unknown field (expected one of: " + list + ")");
      }
    }
  }

  double number() const {
    require();
    if (!node_.IsScalar()) fail("expected a number");
    try {
      const double v = node_.as<double>();
      if (!std::isfinite(v)) fail("expected a finite number, got '" + node_.Scalar() + "'");
      return v;
    } catch (const YAML::Exception&) {
      fail("expected a number, got '" + node_.Scalar() + "'");
    }
  }
  double number_in(double lo, double hi) const {
    const double v = number();
    if (v < lo || v > hi) fail(fmt::format("{} is out of range [{}, {}]", v, lo, hi));
    return v;
  }
  long long integer_in(long long lo, long long hi) const {
    const double v = number();
    if (v != std::floor(v)) fail(fmt::format("expected an integer, got {}", v));
    if (v < static_cast<double>(lo) || v > static_cast<double>(hi))
      fail(fmt::format("{} is out of range [{}, {}]", v, lo, hi));
    return static_cast<long long>(v);
  }
  std::string text() const {
    require();
    if (!node_.IsScalar()) fail("expected a string");
    return node_.Scalar();
  }
  bool boolean() const {
    require();
    if (!node_.IsScalar()) fail("expected true or false");
    try {
      return node_.as<bool>();
    } catch (const YAML::Exception&) {
      fail("expected true or false, got '" + node_.Scalar() + "'");
    }
  }
  /// A list of system names ("gps", "galileo"), each once, at least one.
  std::vector<GnssSystem> system_list() const {
    require();
    if (!node_.IsSequence() || size() == 0) fail("expected a list of systems, e.g. [gps, galileo]");
    std::vector<GnssSystem> systems;
    for (std::size_t i = 0; i < size(); ++i) {
      const Field item = at(i);
      const auto system = parse_system_name(item.text());
      if (!system) item.fail("unknown system '" + item.text() + "' (expected gps or galileo)");
      if (std::find(systems.begin(), systems.end(), *system) != systems.end())
        item.fail("system '" + item.text() + "' is listed twice");
      systems.push_back(*system);
    }
    return systems;
  }
  /// A list of satellites: GPS PRNs as numbers (7) or names (G07), Galileo ones as names
  /// (E11), into `gps` and `galileo`.
  void satellite_list(std::vector<int>& gps, std::vector<int>& galileo) const {
    require();
    if (!node_.IsSequence()) fail("expected a list of satellites (GPS PRNs such as 7 or G07, Galileo such as E11)");
    for (std::size_t i = 0; i < size(); ++i) {
      const Field item = at(i);
      const std::string text = item.text();
      if (!text.empty() && std::isdigit(static_cast<unsigned char>(text[0]))) {
        gps.push_back(static_cast<int>(item.integer_in(1, 32)));
        continue;
      }
      const auto id = parse_satellite_id(text);
      if (!id || (id->system == GnssSystem::gps && id->prn > 32) || (id->system == GnssSystem::galileo && id->prn > 50))
        item.fail("expected a GPS PRN 1..32 (7 or G07) or a Galileo satellite E01..E50, got '" + text + "'");
      (id->system == GnssSystem::gps ? gps : galileo).push_back(id->prn);
    }
  }

 private:
  YAML::Node node_;
  std::string path_;
  const std::string* origin_;
  YAML::Mark parent_mark_;
};

/// The last GPS week a scenario may start in (in 2171), whichever way start_time is written:
/// the date form must not let through a week that the week form (which a scenario is
/// written back in) rejects.
constexpr int kMaxStartWeek = 10000;

/// start_time: "YYYY-MM-DDThh:mm:ss" (GPS time scale) or {week: W, sow: S}.
GpsTime parse_start_time(const Field& f) {
  if (f.is_map()) {
    f.allow_only({"week", "sow"});
    return GpsTime::normalized(static_cast<int>(f["week"].integer_in(0, kMaxStartWeek)),
                               f["sow"].number_in(0, kSecondsPerWeek - 1e-9));
  }
  const std::string s = f.text();
  // Exactly "YYYY-MM-DDThh:mm:ss[.fff]" (or a space for the T): no signs, no trailing text,
  // no "Z" (the scenario's times are GPS time).
  const std::string expected = "expected a GPS time like \"2022-01-01T02:00:00\" or {week: 2190, sow: 525600}";
  const std::optional<IsoDateTime> written = parse_iso_date_time(s, false);
  if (!written) f.fail(expected + ", got '" + s + "'");
  const CalendarTime c = written->calendar;
  if (!is_valid_calendar(c)) f.fail("'" + s + "' is not a real date and time (" + expected.substr(9) + ")");
  const GpsTime t = gps_time_from_calendar(c);
  if (t.week < 0) f.fail("'" + s + "' is before the GPS epoch (1980-01-06)");
  if (t.week > kMaxStartWeek)
    f.fail(fmt::format("'{}' is in GPS week {}, after the last one a scenario may start in ({})", s, t.week,
                       kMaxStartWeek));
  return t;
}

TrajectorySpec parse_trajectory(const Field& f, const std::string& base_dir, const std::string& search_root) {
  f.allow_only({"preset", "file", "start", "heading_deg"});
  TrajectorySpec spec;
  if (f.has("preset") && f.has("file")) f.fail("give either 'preset' or 'file', not both");
  if (f.has("file")) {
    spec.preset.clear();
    spec.csv_path = resolve_path(f["file"].text(), base_dir, search_root);
    if (const auto missing = missing_file_reason(spec.csv_path))
      f["file"].fail("trajectory file '" + spec.csv_path + "' " + *missing);
  } else if (f.has("preset")) {
    spec.preset = f["preset"].text();
  }
  if (f.has("start")) {
    const Field s = f["start"];
    s.allow_only({"lat_deg", "lon_deg", "height_m"});
    spec.start.lat_rad = s["lat_deg"].number_in(-90, 90) * kDegToRad;
    spec.start.lon_rad = s["lon_deg"].number_in(-180, 360) * kDegToRad;
    spec.start.height_m = s.has("height_m") ? s["height_m"].number_in(-500, 100000) : 0.0;
  } else {
    spec.start = {37.5 * kDegToRad, 127.0 * kDegToRad, 50.0};
  }
  if (f.has("heading_deg")) spec.heading_rad = f["heading_deg"].number_in(-360, 360) * kDegToRad;
  return spec;
}

Cn0Spec parse_cn0(const Field& f) {
  Cn0Spec spec;
  if (f.is_scalar()) {  // shorthand: cn0: 45
    spec.fixed_dbhz = f.number_in(0, 80);
    return spec;
  }
  f.allow_only({"model", "dbhz", "zenith_dbhz", "horizon_dbhz", "per_prn", "ramp"});
  const std::string model = f.has("model") ? f["model"].text() : "fixed";
  if (model == "fixed") {
    spec.model = Cn0Spec::Model::fixed;
  } else if (model == "elevation") {
    spec.model = Cn0Spec::Model::elevation;
  } else {
    f["model"].fail("expected 'fixed' or 'elevation', got '" + model + "'");
  }
  if (f.has("dbhz")) spec.fixed_dbhz = f["dbhz"].number_in(0, 80);
  if (f.has("zenith_dbhz")) spec.zenith_dbhz = f["zenith_dbhz"].number_in(0, 80);
  if (f.has("horizon_dbhz")) spec.horizon_dbhz = f["horizon_dbhz"].number_in(0, 80);
  if (spec.horizon_dbhz > spec.zenith_dbhz) f["horizon_dbhz"].fail("must not exceed zenith_dbhz");
  if (f.has("per_prn")) {
    const Field per = f["per_prn"];
    if (!per.is_map()) per.fail("expected a mapping PRN: dB-Hz");
    std::size_t known = 0;
    for (int prn = 1; prn <= 32; ++prn) {
      for (const std::string& key : {std::to_string(prn), SatelliteId{GnssSystem::gps, prn}.to_string()}) {
        if (per.has(key)) {
          spec.per_prn_dbhz[prn] = per[key].number_in(0, 80);
          ++known;
        }
      }
    }
    for (int svid = 1; svid <= 50; ++svid) {
      const std::string key = SatelliteId{GnssSystem::galileo, svid}.to_string();
      if (per.has(key)) {
        spec.galileo_per_svid_dbhz[svid] = per[key].number_in(0, 80);
        ++known;
      }
    }
    if (known != per.size() || spec.per_prn_dbhz.size() + spec.galileo_per_svid_dbhz.size() != per.size())
      per.fail("keys must be GPS PRNs 1..32 (7 or G07) or Galileo satellites E01..E50, each once");
  }
  if (f.has("ramp")) {
    const Field r = f["ramp"];
    r.allow_only({"start_s", "end_s", "delta_db"});
    spec.ramp_start_s = r["start_s"].number_in(0, 1e7);
    spec.ramp_end_s = r["end_s"].number_in(0, 1e7);
    spec.ramp_delta_db = r["delta_db"].number_in(-80, 80);
    if (spec.ramp_end_s <= spec.ramp_start_s) r["end_s"].fail("must be after start_s");
  }
  return spec;
}

ReceiverClockSpec parse_clock(const Field& f) {
  f.allow_only({"bias_s", "drift_sps", "drift_ppm", "oscillator", "h0", "h_minus2"});
  ReceiverClockSpec spec;
  if (f.has("bias_s")) spec.bias_s = f["bias_s"].number_in(-1.0, 1.0);
  if (f.has("drift_sps") && f.has("drift_ppm")) f.fail("give drift_sps or drift_ppm, not both");
  if (f.has("drift_sps")) spec.drift_sps = f["drift_sps"].number_in(-1e-4, 1e-4);
  if (f.has("drift_ppm")) spec.drift_sps = f["drift_ppm"].number_in(-100, 100) * 1e-6;
  if (f.has("oscillator")) spec.oscillator = f["oscillator"].text();
  if (spec.oscillator == "custom") {
    spec.h0 = f["h0"].number_in(0, 1e-15);
    spec.h_minus2 = f["h_minus2"].number_in(0, 1e-15);
  } else if (!set_oscillator_preset(spec, spec.oscillator)) {
    f["oscillator"].fail("expected ideal, tcxo, ocxo or custom, got '" + spec.oscillator + "'");
  }
  return spec;
}

JammerConfig parse_jammer(const Field& f) {
  f.allow_only({"type", "js_db", "offset_hz", "bandwidth_hz", "sweep_period_s", "duty_cycle", "pulse_rate_hz",
                "start_s", "end_s"});
  JammerConfig j;
  const std::string type = f["type"].text();
  try {
    j.type = parse_jammer_type(type);
  } catch (const std::invalid_argument& e) {
    f["type"].fail(e.what());
  }
  j.js_db = f["js_db"].number_in(-50, 120);
  if (f.has("offset_hz")) j.center_offset_hz = f["offset_hz"].number();
  if (f.has("bandwidth_hz")) j.bandwidth_hz = f["bandwidth_hz"].number_in(0, 1e9);
  if (f.has("sweep_period_s")) j.sweep_period_s = f["sweep_period_s"].number_in(0, 1e3);
  if (f.has("duty_cycle")) j.duty_cycle = f["duty_cycle"].number_in(1e-6, 1.0);
  if (f.has("pulse_rate_hz")) j.pulse_rate_hz = f["pulse_rate_hz"].number_in(0, 1e8);
  if (f.has("start_s")) j.start_s = f["start_s"].number_in(0, 1e7);
  if (f.has("end_s")) j.end_s = f["end_s"].number_in(0, 1e7);
  return j;
}

ImuSpec parse_imu(const Field& f, const std::string& base_dir, const std::string& search_root) {
  f.allow_only({"grade", "grades_file", "rate_hz", "lever_arm_m"});
  ImuSpec spec;
  spec.enabled = true;
  if (f.has("grade")) spec.grade = f["grade"].text();
  spec.grades_file =
      resolve_path(f.has("grades_file") ? f["grades_file"].text() : "data/imu_grades.yaml", base_dir, search_root);
  if (const auto missing = missing_file_reason(spec.grades_file))
    f.fail("IMU grades file '" + spec.grades_file + "' " + *missing);
  try {
    load_imu_grade(spec.grades_file, spec.grade);
  } catch (const std::exception& e) {
    f["grade"].fail(e.what());
  }
  if (f.has("rate_hz")) spec.rate_hz = f["rate_hz"].number_in(1, 10000);
  if (f.has("lever_arm_m")) {
    const Field l = f["lever_arm_m"];
    if (!l.is_sequence() || l.size() != 3) l.fail("expected [x, y, z] in metres (body axes)");
    for (std::size_t i = 0; i < 3; ++i) spec.lever_arm_m[i] = l.at(i).number_in(-100, 100);
  }
  return spec;
}

std::vector<OutageSpec> parse_outages(const Field& f) {
  if (!f.is_sequence()) f.fail("expected a list of {start_s, end_s, prns}");
  std::vector<OutageSpec> out;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Field o = f.at(i);
    o.allow_only({"start_s", "end_s", "prns"});
    OutageSpec spec;
    spec.start_s = o["start_s"].number_in(0, 1e7);
    spec.end_s = o["end_s"].number_in(0, 1e7);
    if (spec.end_s <= spec.start_s) o["end_s"].fail("must be after start_s");
    if (o.has("prns")) o["prns"].satellite_list(spec.prns, spec.galileo_prns);
    out.push_back(spec);
  }
  return out;
}

/// multipath: an environment name (shorthand), or {model | environment, parameters}. An
/// environment starts from multipath_for_environment() and the keys given override it;
/// parameters of the other model are rejected, so a misplaced key is not ignored.
MultipathSpec parse_multipath(const Field& f) {
  MultipathSpec spec;
  auto from_environment = [](const Field& e) {
    try {
      return multipath_for_environment(e.text());
    } catch (const std::invalid_argument& err) {
      e.fail(err.what());
    }
  };
  if (f.is_scalar()) return from_environment(f);  // shorthand: multipath: urban
  f.allow_only({"model", "environment", "antenna_height_m", "reflection_coefficient", "below_horizon_gain_db", "echoes",
                "echo_power_db", "echo_rician_k", "mean_excess_delay_m", "echo_lifetime_s", "blocked_probability",
                "mean_blocked_s", "blocked_attenuation_db"});
  if (f.has("model") && f.has("environment")) f.fail("give either 'model' or 'environment', not both");
  if (f.has("environment")) spec = from_environment(f["environment"]);
  if (f.has("model")) {
    try {
      spec.model = parse_multipath_model(f["model"].text());
    } catch (const std::invalid_argument& e) {
      f["model"].fail(e.what());
    }
  }
  const bool ground = spec.model == MultipathSpec::Model::ground;
  const bool land = spec.model == MultipathSpec::Model::land_mobile;
  auto only_for = [&](std::initializer_list<const char*> keys, bool applies, const char* model) {
    for (const char* k : keys)
      if (f.has(k) && !applies)
        f[k].fail(fmt::format("only for model '{}' (this one is '{}')", model, to_string(spec.model)));
  };
  only_for({"antenna_height_m", "reflection_coefficient", "below_horizon_gain_db"}, ground, "ground");
  only_for({"echoes", "echo_power_db", "echo_rician_k", "mean_excess_delay_m", "echo_lifetime_s", "blocked_probability",
            "mean_blocked_s", "blocked_attenuation_db"},
           land, "land-mobile");
  if (f.has("antenna_height_m")) spec.antenna_height_m = f["antenna_height_m"].number_in(0, 100);
  if (f.has("reflection_coefficient")) spec.reflection_coefficient = f["reflection_coefficient"].number_in(0, 1);
  if (f.has("below_horizon_gain_db")) spec.below_horizon_gain_db = f["below_horizon_gain_db"].number_in(-60, 0);
  if (f.has("echoes")) spec.echoes = static_cast<int>(f["echoes"].integer_in(0, MultipathSpec::kMaxEchoes));
  if (f.has("echo_power_db")) spec.echo_power_db = f["echo_power_db"].number_in(-60, 10);
  if (f.has("echo_rician_k")) spec.echo_rician_k = f["echo_rician_k"].number_in(0, 1000);
  if (f.has("mean_excess_delay_m")) spec.mean_excess_delay_m = f["mean_excess_delay_m"].number_in(0.1, 3000);
  if (f.has("echo_lifetime_s")) spec.echo_lifetime_s = f["echo_lifetime_s"].number_in(0.01, 1e5);
  if (f.has("blocked_probability")) spec.blocked_probability = f["blocked_probability"].number_in(0, 0.95);
  if (f.has("mean_blocked_s")) spec.mean_blocked_s = f["mean_blocked_s"].number_in(0.01, 1e5);
  if (f.has("blocked_attenuation_db")) spec.blocked_attenuation_db = f["blocked_attenuation_db"].number_in(0, 100);
  return spec;
}

/// Reads `text` as one of `names` (the enum value at the same position).
template <typename Enum>
Enum parse_choice(const Field& f, std::initializer_list<std::pair<const char*, Enum>> names) {
  const std::string v = f.text();
  std::string list;
  for (const auto& [name, value] : names) {
    if (v == name) return value;
    list += (list.empty() ? "" : ", ") + std::string(name);
  }
  f.fail("expected one of " + list + ", got '" + v + "'");
}

constexpr std::initializer_list<std::pair<const char*, IonosphereTruthSpec::Model>> kIonoModels{
    {"klobuchar", IonosphereTruthSpec::Model::klobuchar}, {"thin-shell", IonosphereTruthSpec::Model::thin_shell}};
constexpr std::initializer_list<std::pair<const char*, TroposphereTruthSpec::Model>> kTropoModels{
    {"saastamoinen-standard", TroposphereTruthSpec::Model::saastamoinen_standard},
    {"site", TroposphereTruthSpec::Model::site}};
constexpr std::initializer_list<std::pair<const char*, TroposphereTruthSpec::Mapping>> kTropoMappings{
    {"niell", TroposphereTruthSpec::Mapping::niell}, {"black-eisner", TroposphereTruthSpec::Mapping::black_eisner}};
constexpr std::initializer_list<std::pair<const char*, AntennaSpec::Pattern>> kAntennaPatterns{
    {"isotropic", AntennaSpec::Pattern::isotropic}, {"patch", AntennaSpec::Pattern::patch}};

template <typename Enum>
const char* choice_name(std::initializer_list<std::pair<const char*, Enum>> names, Enum value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

/// errors: {preset, ionosphere, troposphere, orbit_clock, antenna, multipath}: the preset's
/// values, then every field given explicitly.
ErrorSpec parse_errors(const Field& f) {
  f.allow_only({"preset", "ionosphere", "troposphere", "orbit_clock", "antenna", "multipath"});
  ErrorSpec e;
  if (f.has("preset")) {
    try {
      e = error_preset(f["preset"].text());
    } catch (const std::invalid_argument& x) {
      f["preset"].fail(x.what());
    }
  }
  if (f.has("ionosphere")) {
    const Field i = f["ionosphere"];
    i.allow_only({"model", "vtec_scale", "day_vtec_tecu", "night_vtec_tecu", "shell_height_km", "disturbance_rms"});
    IonosphereTruthSpec& s = e.ionosphere;
    if (i.has("model")) s.model = parse_choice(i["model"], kIonoModels);
    if (i.has("vtec_scale")) s.vtec_scale = i["vtec_scale"].number_in(0, 10);
    if (i.has("day_vtec_tecu")) s.day_vtec_tecu = i["day_vtec_tecu"].number_in(0, 300);
    if (i.has("night_vtec_tecu")) s.night_vtec_tecu = i["night_vtec_tecu"].number_in(0, 300);
    if (i.has("shell_height_km")) s.shell_height_m = i["shell_height_km"].number_in(100, 2000) * 1000.0;
    if (i.has("disturbance_rms")) s.disturbance_rms = i["disturbance_rms"].number_in(0, 0.5);
    if (s.night_vtec_tecu > s.day_vtec_tecu)
      (i.has("night_vtec_tecu") ? i["night_vtec_tecu"] : i)
          .fail(fmt::format("night_vtec_tecu {} must not exceed day_vtec_tecu {}", s.night_vtec_tecu, s.day_vtec_tecu));
  }
  if (f.has("troposphere")) {
    const Field t = f["troposphere"];
    t.allow_only(
        {"model", "pressure_hpa", "temperature_c", "relative_humidity", "wet_random_walk_m_per_sqrt_h", "mapping"});
    TroposphereTruthSpec& s = e.troposphere;
    if (t.has("model")) s.model = parse_choice(t["model"], kTropoModels);
    if (t.has("pressure_hpa")) s.pressure_hpa = t["pressure_hpa"].number_in(500, 1100);
    if (t.has("temperature_c")) s.temperature_c = t["temperature_c"].number_in(-60, 50);
    if (t.has("relative_humidity")) s.relative_humidity = t["relative_humidity"].number_in(0, 1);
    if (t.has("wet_random_walk_m_per_sqrt_h"))
      s.wet_random_walk_m_per_sqrt_h = t["wet_random_walk_m_per_sqrt_h"].number_in(0, 0.2);
    if (t.has("mapping")) s.mapping = parse_choice(t["mapping"], kTropoMappings);
  }
  if (f.has("orbit_clock")) {
    const Field o = f["orbit_clock"];
    o.allow_only({"radial_m", "along_m", "cross_m", "clock_m", "correlation_time_s"});
    OrbitClockErrorSpec& s = e.orbit_clock;
    if (o.has("radial_m")) s.radial_m = o["radial_m"].number_in(0, 100);
    if (o.has("along_m")) s.along_m = o["along_m"].number_in(0, 100);
    if (o.has("cross_m")) s.cross_m = o["cross_m"].number_in(0, 100);
    if (o.has("clock_m")) s.clock_m = o["clock_m"].number_in(0, 100);
    if (o.has("correlation_time_s")) s.correlation_time_s = o["correlation_time_s"].number_in(60, 1e6);
  }
  if (f.has("antenna")) {
    const Field a = f["antenna"];
    a.allow_only({"pattern", "gain_10deg_db", "gain_horizon_db"});
    AntennaSpec& s = e.antenna;
    if (a.has("pattern")) s.pattern = parse_choice(a["pattern"], kAntennaPatterns);
    if (a.has("gain_10deg_db")) s.gain_10deg_db = a["gain_10deg_db"].number_in(-30, 0);
    if (a.has("gain_horizon_db")) s.gain_horizon_db = a["gain_horizon_db"].number_in(-40, 0);
    if (!(s.gain_horizon_db < s.gain_10deg_db && s.gain_10deg_db < 0.0))
      (a.has("gain_10deg_db") ? a["gain_10deg_db"] : a)
          .fail(fmt::format("need gain_horizon_db < gain_10deg_db < 0, got {} and {}", s.gain_horizon_db,
                            s.gain_10deg_db));
  }
  if (f.has("multipath")) e.multipath = parse_multipath(f["multipath"]);
  return e;
}

}  // namespace

bool set_oscillator_preset(ReceiverClockSpec& spec, const std::string& name) {
  // Allan variance coefficients. h_-2 (random-walk FM) from Brown & Hwang, Introduction to
  // Random Signals, table 9.1. Their h0 lumps flicker into white FM for Kalman-filter clock
  // models at second scales; used as white FM millisecond by millisecond it gives ~30 deg
  // RMS of L1 phase jitter in a 10 Hz PLL, far more than real oscillators. Here h0 is the
  // white-FM floor (TCXO: sigma_y(1 s) ~ 3e-11, OCXO ~ 2e-11), a few degrees of jitter.
  if (name == "ideal") {
    spec.h0 = spec.h_minus2 = 0.0;
  } else if (name == "tcxo") {
    spec.h0 = 2e-21;
    spec.h_minus2 = 2e-20;
  } else if (name == "ocxo") {
    spec.h0 = 8e-22;
    spec.h_minus2 = 4e-23;
  } else {
    return false;
  }
  spec.oscillator = name;
  return true;
}

Scenario parse_scenario(const std::string& yaml_text, const std::string& origin, const std::string& base_dir,
                        const std::string& search_root) {
  YAML::Node root;
  try {
    root = load_checked_yaml(yaml_text, origin);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(fmt::format("{}:{}: not valid YAML/JSON: {}", origin, e.mark.line + 1, e.msg));
  }
  const Field f(root, "", &origin);
  if (!root.IsMap()) throw std::invalid_argument(origin + ": expected a scenario mapping at the top level");
  f.allow_only({"name",
                "start_time",
                "duration_s",
                "sample_rate_hz",
                "if_hz",
                "format",
                "adc",
                "nav_file",
                "systems",
                "trajectory",
                "elevation_mask_deg",
                "prns",
                "max_satellites",
                "cn0",
                "receiver_clock",
                "ionosphere",
                "troposphere",
                "errors",
                "seed",
                "jammers",
                "outages",
                "imu",
                "truth_rate_hz",
                "sat_truth_rate_hz"});
  Scenario s;
  s.source_path = origin;
  s.name = f.has("name") ? f["name"].text() : std::filesystem::path(origin).stem().string();
  if (!f.has("start_time")) f.fail("missing required field 'start_time'");
  s.start_time = parse_start_time(f["start_time"]);
  if (!f.has("duration_s")) f.fail("missing required field 'duration_s'");
  s.duration_s = f["duration_s"].number();
  if (s.duration_s <= 0) f["duration_s"].fail(fmt::format("must be positive, got {}", s.duration_s));
  if (s.duration_s > 86400) f["duration_s"].fail("must be at most 86400 s");
  if (f.has("sample_rate_hz")) s.sample_rate_hz = f["sample_rate_hz"].number_in(1e5, 1e8);
  if (std::floor(s.sample_rate_hz) != s.sample_rate_hz) f["sample_rate_hz"].fail("must be a whole number of Hz");
  if (f.has("if_hz")) s.if_hz = f["if_hz"].number_in(-s.sample_rate_hz / 2, s.sample_rate_hz / 2);
  if (f.has("format")) {
    try {
      s.format = parse_sample_format(f["format"].text());
    } catch (const std::invalid_argument& e) {
      f["format"].fail(e.what());
    }
  }
  if (f.has("adc")) {
    const Field a = f["adc"];
    a.allow_only({"bits", "agc", "agc_time_constant_s"});
    if (a.has("bits")) s.adc.bits = static_cast<int>(a["bits"].integer_in(0, 16));
    if (a.has("agc")) s.adc.agc = a["agc"].boolean();
    if (a.has("agc_time_constant_s")) s.adc.agc_time_constant_s = a["agc_time_constant_s"].number_in(1e-6, 100);
  }
  const std::string nav = f.has("nav_file") ? f["nav_file"].text() : "data/brdc0010.22n";
  s.nav_file = resolve_path(nav, base_dir, search_root);
  if (const auto missing = missing_file_reason(s.nav_file)) {
    if (f.has("nav_file")) f["nav_file"].fail("navigation file '" + s.nav_file + "' " + *missing);
    throw std::invalid_argument(origin + ": default navigation file '" + s.nav_file + "' " + *missing +
                                " (set nav_file)");
  }
  if (f.has("systems")) s.systems = f["systems"].system_list();
  if (f.has("trajectory")) s.trajectory = parse_trajectory(f["trajectory"], base_dir, search_root);
  if (f.has("elevation_mask_deg")) s.elevation_mask_rad = f["elevation_mask_deg"].number_in(-10, 90) * kDegToRad;
  if (f.has("prns")) f["prns"].satellite_list(s.prns, s.galileo_prns);
  if (f.has("max_satellites")) s.max_satellites = static_cast<int>(f["max_satellites"].integer_in(1, 32));
  if (f.has("cn0")) s.cn0 = parse_cn0(f["cn0"]);
  if (f.has("receiver_clock")) s.clock = parse_clock(f["receiver_clock"]);
  if (f.has("ionosphere")) s.ionosphere = f["ionosphere"].boolean();
  if (f.has("troposphere")) s.troposphere = f["troposphere"].boolean();
  if (f.has("errors")) s.errors = parse_errors(f["errors"]);
  if (f.has("seed")) s.seed = static_cast<std::uint64_t>(f["seed"].integer_in(0, (1LL << 53)));
  if (f.has("jammers")) {
    const Field j = f["jammers"];
    if (!j.is_sequence()) j.fail("expected a list of jammers");
    for (std::size_t i = 0; i < j.size(); ++i) s.jammers.push_back(parse_jammer(j.at(i)));
  }
  if (f.has("outages")) s.outages = parse_outages(f["outages"]);
  if (f.has("imu")) s.imu = parse_imu(f["imu"], base_dir, search_root);
  if (f.has("truth_rate_hz")) s.truth_rate_hz = f["truth_rate_hz"].number_in(0.1, 1000);
  if (f.has("sat_truth_rate_hz")) s.sat_truth_rate_hz = f["sat_truth_rate_hz"].number_in(0.1, 1000);
  try {
    validate_scenario(s);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(origin + ": " + e.what());
  }
  return s;
}

void validate_scenario(const Scenario& s) {
  if (!is_complex(s.format) && s.if_hz == 0.0)
    throw std::invalid_argument(
        fmt::format("field 'if_hz': real sample format '{}' needs a non-zero IF (the signal would alias onto itself)",
                    to_string(s.format)));
  if (!is_complex(s.format) && std::abs(s.if_hz) + 1.1e6 > s.sample_rate_hz / 2)
    throw std::invalid_argument(fmt::format(
        "field 'if_hz': real sampling at {} Hz cannot hold the 2 MHz C/A band at IF {} Hz", s.sample_rate_hz, s.if_hz));
  if (s.sample_rate_hz < 1.023e6 * 1.0)
    throw std::invalid_argument("field 'sample_rate_hz': must be at least 1.023 MHz for the C/A code");
  // The synthesizer works in 1 ms epochs of a whole number of samples.
  if (std::fmod(s.sample_rate_hz, 1000.0) != 0.0)
    throw std::invalid_argument(
        fmt::format("field 'sample_rate_hz': {} Hz is not a multiple of 1000 Hz", s.sample_rate_hz));
  if (s.duration_s < 1e-3) throw std::invalid_argument("field 'duration_s': must be at least 0.001 s");
  for (const auto& [name, rate] : {std::pair<const char*, double>{"truth_rate_hz", s.truth_rate_hz},
                                   std::pair<const char*, double>{"sat_truth_rate_hz", s.sat_truth_rate_hz}}) {
    const double stride = 1000.0 / rate;
    if (std::abs(stride - std::round(stride)) > 1e-9)
      throw std::invalid_argument(
          fmt::format("field '{}': {} Hz does not divide 1000 Hz (truth rows fall on whole milliseconds)", name, rate));
  }
  if (const auto spw = samples_per_word(s.format);
      std::llround(s.sample_rate_hz / 1000.0) % static_cast<long long>(spw) != 0)
    throw std::invalid_argument(fmt::format(
        "field 'sample_rate_hz': {} Hz gives {} samples a millisecond, not whole words of format '{}' ({} samples "
        "a word)",
        s.sample_rate_hz, std::llround(s.sample_rate_hz / 1000.0), to_string(s.format), spw));
  const int max_bits = value_bits(s.format);
  if (s.adc.bits > max_bits)
    throw std::invalid_argument(fmt::format("field 'adc.bits': {} bits do not fit format '{}' (at most {})", s.adc.bits,
                                            to_string(s.format), max_bits));
  for (std::size_t i = 0; i < s.jammers.size(); ++i) {
    try {
      validate_jammer(s.jammers[i], s.sample_rate_hz, s.if_hz);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("field 'jammers[{}]': {}", i, e.what()));
    }
  }
}

void require_scenario_systems(const Scenario& s, const std::vector<GnssSystem>& systems, const std::string& name) {
  for (GnssSystem system : systems)
    if (!includes_system(s.systems, system))
      throw InputError(fmt::format("--systems {}: scenario '{}' has no {} satellites (its systems: {})",
                                   systems_list(systems), name, system_name(system), systems_list(s.systems)));
}

Scenario load_scenario(const std::string& path, const std::string& search_root) {
  try {
    check_input_file(path, "scenario file", kMaxScenarioBytes);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(e.what());
  }
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot open scenario file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  if (text.str().find_first_not_of(" \t\r\n") == std::string::npos)
    throw std::invalid_argument("scenario file '" + path + "' is empty");
  const std::string base_dir = std::filesystem::absolute(path).parent_path().string();
  return parse_scenario(text.str(), path, base_dir, search_root);
}

std::string scenario_to_yaml(const Scenario& s) {
  constexpr double r2d = 180.0 / 3.14159265358979323846;
  YAML::Emitter out;
  out.SetDoublePrecision(15);
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << s.name;
  out << YAML::Key << "start_time" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "week" << YAML::Value
      << s.start_time.week << YAML::Key << "sow" << YAML::Value << s.start_time.sow << YAML::EndMap;
  out << YAML::Key << "duration_s" << YAML::Value << s.duration_s;
  out << YAML::Key << "sample_rate_hz" << YAML::Value << s.sample_rate_hz;
  out << YAML::Key << "if_hz" << YAML::Value << s.if_hz;
  out << YAML::Key << "format" << YAML::Value << std::string(to_string(s.format));
  out << YAML::Key << "adc" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "bits" << YAML::Value
      << s.adc.bits << YAML::Key << "agc" << YAML::Value << s.adc.agc << YAML::Key << "agc_time_constant_s"
      << YAML::Value << s.adc.agc_time_constant_s << YAML::EndMap;
  out << YAML::Key << "nav_file" << YAML::Value << s.nav_file;
  // Written only when not the default, which keeps a GPS-only scenario's copy as it was.
  if (!is_gps_only(s.systems)) {
    std::vector<std::string> names;
    for (GnssSystem system : s.systems) names.emplace_back(system_name(system));
    out << YAML::Key << "systems" << YAML::Value << YAML::Flow << names;
  }
  out << YAML::Key << "trajectory" << YAML::Value << YAML::BeginMap;
  if (!s.trajectory.csv_path.empty()) {
    out << YAML::Key << "file" << YAML::Value << s.trajectory.csv_path;
  } else {
    out << YAML::Key << "preset" << YAML::Value << s.trajectory.preset;
  }
  out << YAML::Key << "start" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "lat_deg" << YAML::Value
      << s.trajectory.start.lat_rad * r2d << YAML::Key << "lon_deg" << YAML::Value << s.trajectory.start.lon_rad * r2d
      << YAML::Key << "height_m" << YAML::Value << s.trajectory.start.height_m << YAML::EndMap;
  out << YAML::Key << "heading_deg" << YAML::Value << s.trajectory.heading_rad * r2d << YAML::EndMap;
  out << YAML::Key << "elevation_mask_deg" << YAML::Value << s.elevation_mask_rad * r2d;
  if (!s.galileo_prns.empty()) {
    out << YAML::Key << "prns" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int prn : s.prns) out << prn;
    for (int svid : s.galileo_prns) out << SatelliteId{GnssSystem::galileo, svid}.to_string();
    out << YAML::EndSeq;
  } else if (!s.prns.empty()) {
    out << YAML::Key << "prns" << YAML::Value << YAML::Flow << s.prns;
  }
  out << YAML::Key << "max_satellites" << YAML::Value << s.max_satellites;
  out << YAML::Key << "cn0" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << (s.cn0.model == Cn0Spec::Model::fixed ? "fixed" : "elevation");
  out << YAML::Key << "dbhz" << YAML::Value << s.cn0.fixed_dbhz;
  out << YAML::Key << "zenith_dbhz" << YAML::Value << s.cn0.zenith_dbhz;
  out << YAML::Key << "horizon_dbhz" << YAML::Value << s.cn0.horizon_dbhz;
  if (!s.cn0.per_prn_dbhz.empty() || !s.cn0.galileo_per_svid_dbhz.empty()) {
    out << YAML::Key << "per_prn" << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const auto& [prn, v] : s.cn0.per_prn_dbhz) out << YAML::Key << std::to_string(prn) << YAML::Value << v;
    for (const auto& [svid, v] : s.cn0.galileo_per_svid_dbhz)
      out << YAML::Key << SatelliteId{GnssSystem::galileo, svid}.to_string() << YAML::Value << v;
    out << YAML::EndMap;
  }
  if (s.cn0.ramp_end_s > s.cn0.ramp_start_s)
    out << YAML::Key << "ramp" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "start_s" << YAML::Value
        << s.cn0.ramp_start_s << YAML::Key << "end_s" << YAML::Value << s.cn0.ramp_end_s << YAML::Key << "delta_db"
        << YAML::Value << s.cn0.ramp_delta_db << YAML::EndMap;
  out << YAML::EndMap;
  out << YAML::Key << "receiver_clock" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "bias_s"
      << YAML::Value << s.clock.bias_s << YAML::Key << "drift_sps" << YAML::Value << s.clock.drift_sps << YAML::Key
      << "oscillator" << YAML::Value << "custom" << YAML::Key << "h0" << YAML::Value << s.clock.h0 << YAML::Key
      << "h_minus2" << YAML::Value << s.clock.h_minus2 << YAML::EndMap;
  out << YAML::Key << "ionosphere" << YAML::Value << s.ionosphere;
  out << YAML::Key << "troposphere" << YAML::Value << s.troposphere;
  {
    // Every effective value, so the file reproduces the run even if a preset changes later.
    const ErrorSpec& e = s.errors;
    out << YAML::Key << "errors" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "preset" << YAML::Value << e.preset;
    out << YAML::Key << "ionosphere" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "model"
        << YAML::Value << choice_name(kIonoModels, e.ionosphere.model) << YAML::Key << "vtec_scale" << YAML::Value
        << e.ionosphere.vtec_scale << YAML::Key << "day_vtec_tecu" << YAML::Value << e.ionosphere.day_vtec_tecu
        << YAML::Key << "night_vtec_tecu" << YAML::Value << e.ionosphere.night_vtec_tecu << YAML::Key
        << "shell_height_km" << YAML::Value << e.ionosphere.shell_height_m / 1000.0 << YAML::Key << "disturbance_rms"
        << YAML::Value << e.ionosphere.disturbance_rms << YAML::EndMap;
    out << YAML::Key << "troposphere" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "model"
        << YAML::Value << choice_name(kTropoModels, e.troposphere.model) << YAML::Key << "pressure_hpa" << YAML::Value
        << e.troposphere.pressure_hpa << YAML::Key << "temperature_c" << YAML::Value << e.troposphere.temperature_c
        << YAML::Key << "relative_humidity" << YAML::Value << e.troposphere.relative_humidity << YAML::Key
        << "wet_random_walk_m_per_sqrt_h" << YAML::Value << e.troposphere.wet_random_walk_m_per_sqrt_h << YAML::Key
        << "mapping" << YAML::Value << choice_name(kTropoMappings, e.troposphere.mapping) << YAML::EndMap;
    out << YAML::Key << "orbit_clock" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "radial_m"
        << YAML::Value << e.orbit_clock.radial_m << YAML::Key << "along_m" << YAML::Value << e.orbit_clock.along_m
        << YAML::Key << "cross_m" << YAML::Value << e.orbit_clock.cross_m << YAML::Key << "clock_m" << YAML::Value
        << e.orbit_clock.clock_m << YAML::Key << "correlation_time_s" << YAML::Value << e.orbit_clock.correlation_time_s
        << YAML::EndMap;
    out << YAML::Key << "antenna" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "pattern"
        << YAML::Value << choice_name(kAntennaPatterns, e.antenna.pattern) << YAML::Key << "gain_10deg_db"
        << YAML::Value << e.antenna.gain_10deg_db << YAML::Key << "gain_horizon_db" << YAML::Value
        << e.antenna.gain_horizon_db << YAML::EndMap;
    {
      const MultipathSpec& m = e.multipath;
      out << YAML::Key << "multipath" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "model"
          << YAML::Value << std::string(to_string(m.model));
      if (m.model == MultipathSpec::Model::ground) {
        out << YAML::Key << "antenna_height_m" << YAML::Value << m.antenna_height_m << YAML::Key
            << "reflection_coefficient" << YAML::Value << m.reflection_coefficient << YAML::Key
            << "below_horizon_gain_db" << YAML::Value << m.below_horizon_gain_db;
      } else if (m.model == MultipathSpec::Model::land_mobile) {
        out << YAML::Key << "echoes" << YAML::Value << m.echoes << YAML::Key << "echo_power_db" << YAML::Value
            << m.echo_power_db << YAML::Key << "echo_rician_k" << YAML::Value << m.echo_rician_k << YAML::Key
            << "mean_excess_delay_m" << YAML::Value << m.mean_excess_delay_m << YAML::Key << "echo_lifetime_s"
            << YAML::Value << m.echo_lifetime_s << YAML::Key << "blocked_probability" << YAML::Value
            << m.blocked_probability << YAML::Key << "mean_blocked_s" << YAML::Value << m.mean_blocked_s << YAML::Key
            << "blocked_attenuation_db" << YAML::Value << m.blocked_attenuation_db;
      }
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::Key << "seed" << YAML::Value << s.seed;
  if (!s.jammers.empty()) {
    out << YAML::Key << "jammers" << YAML::Value << YAML::BeginSeq;
    for (const auto& j : s.jammers) {
      out << YAML::Flow << YAML::BeginMap << YAML::Key << "type" << YAML::Value << std::string(to_string(j.type))
          << YAML::Key << "js_db" << YAML::Value << j.js_db << YAML::Key << "offset_hz" << YAML::Value
          << j.center_offset_hz << YAML::Key << "bandwidth_hz" << YAML::Value << j.bandwidth_hz << YAML::Key
          << "sweep_period_s" << YAML::Value << j.sweep_period_s << YAML::Key << "duty_cycle" << YAML::Value
          << j.duty_cycle << YAML::Key << "pulse_rate_hz" << YAML::Value << j.pulse_rate_hz << YAML::Key << "start_s"
          << YAML::Value << j.start_s << YAML::Key << "end_s" << YAML::Value << j.end_s << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  if (!s.outages.empty()) {
    out << YAML::Key << "outages" << YAML::Value << YAML::BeginSeq;
    for (const auto& o : s.outages) {
      out << YAML::Flow << YAML::BeginMap << YAML::Key << "start_s" << YAML::Value << o.start_s << YAML::Key << "end_s"
          << YAML::Value << o.end_s;
      if (!o.galileo_prns.empty()) {
        out << YAML::Key << "prns" << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (int prn : o.prns) out << prn;
        for (int svid : o.galileo_prns) out << SatelliteId{GnssSystem::galileo, svid}.to_string();
        out << YAML::EndSeq;
      } else if (!o.prns.empty()) {
        out << YAML::Key << "prns" << YAML::Value << YAML::Flow << o.prns;
      }
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  if (s.imu.enabled) {
    out << YAML::Key << "imu" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "grade" << YAML::Value
        << s.imu.grade << YAML::Key << "grades_file" << YAML::Value << s.imu.grades_file << YAML::Key << "rate_hz"
        << YAML::Value << s.imu.rate_hz << YAML::Key << "lever_arm_m" << YAML::Value << YAML::Flow << YAML::BeginSeq
        << s.imu.lever_arm_m[0] << s.imu.lever_arm_m[1] << s.imu.lever_arm_m[2] << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::Key << "truth_rate_hz" << YAML::Value << s.truth_rate_hz;
  out << YAML::Key << "sat_truth_rate_hz" << YAML::Value << s.sat_truth_rate_hz;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace deepnav
