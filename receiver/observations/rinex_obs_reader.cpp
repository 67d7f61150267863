#include "receiver/observations/rinex_obs_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <stdexcept>
#include <string_view>

#include "signals/gps_constants.hpp"
#include "signals/rinex_fields.hpp"

namespace deepnav {
namespace {

constexpr double kMillisecondRange_m = gps::kSpeedOfLight_mps * 1e-3;
/// BDT = GPS time - 14 s (BDT began on 2006-01-01, when GPS - UTC was 14 s).
constexpr int kBdtBehindGps_s = 14;

using rinex::column;
using rinex::parse_number;
using rinex::trim;

int parse_int(std::string_view field, const char* what, int lo, int hi) {
  const auto v = parse_number(field);
  if (!v) throw std::invalid_argument(fmt::format("{} is blank", what));
  const double r = std::round(*v);
  if (std::abs(*v - r) > 1e-9 || r < lo || r > hi)
    throw std::invalid_argument(
        fmt::format("{} must be a whole number in [{}, {}], got '{}'", what, lo, hi, trim(field)));
  return static_cast<int>(r);
}

class LineReader {
 public:
  LineReader(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}
  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++line_no_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (captured_ != nullptr) captured_->push_back(line);
    return true;
  }
  /// From now on every line read is also appended to `lines` (nullptr: no longer).
  void capture_into(std::vector<std::string>* lines) { captured_ = lines; }
  const std::string& name() const { return name_; }
  /// The next line, or an error saying what was expected there.
  std::string require(const std::string& what) {
    std::string line;
    if (!next(line)) fail(line_no_ + 1, fmt::format("file ends where {} was expected (truncated file?)", what));
    return line;
  }
  int line_no() const { return line_no_; }
  [[noreturn]] void fail(int line_no, const std::string& message) const {
    throw std::runtime_error(fmt::format("{}:{}: {}", name_, line_no, message));
  }
  [[noreturn]] void fail(const std::string& message) const { fail(line_no_, message); }

 private:
  std::istream& in_;
  std::string name_;
  int line_no_ = 0;
  std::vector<std::string>* captured_ = nullptr;
};

template <typename F>
auto with_context(const LineReader& reader, const std::string& context, F&& parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    reader.fail(fmt::format("{}: {}", context, e.what()));
  }
}

/// The observation types of one system and where the L1 C/A (GPS) or E1 pilot (Galileo,
/// the same C1C L1C D1C S1C codes) ones are.
struct GpsTypes {
  std::vector<std::string> all;  ///< every observation type of the system, in file order
  int pseudorange = -1, phase = -1, doppler = -1, cn0 = -1;
};

struct Header {
  double version = 0.0;
  bool v2 = false;
  char file_system = 'G';
  GpsTypes gps;
  std::map<char, int> type_counts;  ///< number of observation types per system
  /// SYS / SCALE FACTOR of the GPS types (RINEX 3): stored values are divided by it.
  std::map<std::string, double> gps_scale;
  std::optional<double> gps_scale_all;  ///< one factor for every GPS type
  GpsTypes galileo;                     ///< RINEX 3 only
  std::map<std::string, double> galileo_scale;
  std::optional<double> galileo_scale_all;
  /// Galileo satellites are read (RINEX 3 with an E1 C1C pseudorange type); else skipped.
  bool reads_galileo() const { return !v2 && galileo.pseudorange >= 0; }
  std::optional<double> interval_s;
  int interval_line = 0;
  std::optional<Eigen::Vector3d> approx_position;
  std::string time_system;  ///< TIME OF FIRST OBS, columns 49-51 (blank: the file's system's)
  int time_system_line = 0;
  std::optional<int> leap_seconds;  ///< GPS - UTC, from LEAP SECONDS
};

std::string_view label(std::string_view line) { return trim(column(line, 60, 20)); }

/// RINEX 2 names a system by one letter; blank means GPS.
char system_letter(char c) { return c == ' ' ? 'G' : c; }

void locate_l1(GpsTypes& types, bool rinex2) {
  const std::array<const char*, 4> codes3 = {"C1C", "L1C", "D1C", "S1C"};
  const std::array<const char*, 4> codes2 = {"C1", "L1", "D1", "S1"};
  const auto& codes = rinex2 ? codes2 : codes3;
  types.pseudorange = types.phase = types.doppler = types.cn0 = -1;
  std::array<int*, 4> slots = {&types.pseudorange, &types.phase, &types.doppler, &types.cn0};
  for (std::size_t k = 0; k < codes.size(); ++k) {
    const auto it = std::find(types.all.begin(), types.all.end(), codes[k]);
    if (it != types.all.end()) *slots[k] = static_cast<int>(it - types.all.begin());
  }
}

/// The header records that say how the observation records read, one line at a time:
/// those of the file's header, and those an event epoch (flags 2-5) carries, which apply
/// from there on (observation types, scale factors, the interval). A record spanning lines
/// (a type list) goes on at the next line; finish() says where a block of records ends.
class HeaderRecords {
 public:
  HeaderRecords(Header& h, LineReader& reader) : h_(h), reader_(reader) {}

  void apply(const std::string& line) {
    const std::string_view lab = label(line);
    if (lab == "SYS / # / OBS TYPES" && !h_.v2) obs_types_v3(line);
    else if (lab == "# / TYPES OF OBSERV" && h_.v2) obs_types_v2(line);
    else if (lab == "SYS / SCALE FACTOR" && !h_.v2) scale_factor(line);
    else if (lab == "INTERVAL") interval(line);
    else if (lab == "TIME OF FIRST OBS") time_system(line);
    else if (lab == "LEAP SECONDS") leap_seconds(line);
    else if (lab == "APPROX POSITION XYZ") approx_position(line);
  }

  /// The records end here (`where`: the header, or the event at a line): nothing may still
  /// be announced, and the GPS types must hold an L1 C/A pseudorange.
  void finish(const std::string& where) {
    if (remaining_ > 0)
      reader_.fail(fmt::format("{} ends with {} observation types still announced", where, remaining_));
    if (scale_remaining_ > 0)
      reader_.fail(fmt::format("{} ends with {} scale factor types still announced", where, scale_remaining_));
    locate_l1(h_.gps, h_.v2);
    if (h_.v2) h_.galileo = {};
    locate_l1(h_.galileo, h_.v2);
    const char* record = h_.v2 ? "# / TYPES OF OBSERV" : "SYS / # / OBS TYPES";
    // A Galileo-only file reads without GPS types.
    if (h_.gps.all.empty() && h_.reads_galileo()) return;
    if (h_.gps.all.empty())
      reader_.fail(fmt::format("no GPS observation types (nor Galileo ones with C1C) in {} ({}): nothing to read",
                               where, record));
    if (h_.gps.pseudorange < 0)
      reader_.fail(fmt::format("the GPS observation types of {} have no L1 C/A pseudorange ({}); they are: {}", where,
                               h_.v2 ? "C1" : "C1C", fmt::join(h_.gps.all, " ")));
  }

  int type_records() const { return type_records_; }

 private:
  void obs_types_v3(const std::string& line) {
    char sys = line.empty() ? ' ' : line[0];
    if (sys == ' ') {
      if (continuing_ == 0) reader_.fail("SYS / # / OBS TYPES: continuation line without a system line before it");
      sys = continuing_;
    } else {
      remaining_ = with_context(reader_, fmt::format("SYS / # / OBS TYPES of '{}': number of types (columns 4-6)", sys),
                                [&] { return parse_int(column(line, 3, 3), "number of types", 1, 999); });
      h_.type_counts[sys] = remaining_;
      // A new list replaces the one before.
      if (sys == 'G') h_.gps.all.clear();
      if (sys == 'E') h_.galileo.all.clear();
      ++type_records_;
    }
    for (int k = 0; k < 13 && remaining_ > 0; ++k, --remaining_) {
      const std::string code(trim(column(line, 7 + 4 * static_cast<std::size_t>(k), 3)));
      if (code.size() != 3)
        reader_.fail(
            fmt::format("SYS / # / OBS TYPES of '{}': type {} (columns {}-{}) is '{}', expected a 3-character "
                        "code such as C1C",
                        sys, k + 1, 8 + 4 * k, 10 + 4 * k, code));
      if (sys == 'G') h_.gps.all.push_back(code);
      if (sys == 'E') h_.galileo.all.push_back(code);
    }
    continuing_ = remaining_ > 0 ? sys : 0;
  }

  void obs_types_v2(const std::string& line) {
    if (!trim(column(line, 0, 6)).empty()) {
      remaining_ = with_context(reader_, "# / TYPES OF OBSERV: number of types (columns 1-6)",
                                [&] { return parse_int(column(line, 0, 6), "number of types", 1, 99); });
      for (char s : std::string("GRESJCI")) h_.type_counts[s] = remaining_;
      h_.gps.all.clear();  // a new list replaces the one before
      ++type_records_;
    } else if (remaining_ == 0) {
      reader_.fail("# / TYPES OF OBSERV: continuation line without a count line before it");
    }
    for (int k = 0; k < 9 && remaining_ > 0; ++k, --remaining_) {
      const std::string code(trim(column(line, 6 + 6 * static_cast<std::size_t>(k), 6)));
      if (code.size() != 2)
        reader_.fail(
            fmt::format("# / TYPES OF OBSERV: type {} (columns {}-{}) is '{}', expected a 2-character code "
                        "such as C1",
                        k + 1, 11 + 6 * k, 12 + 6 * k, code));
      h_.gps.all.push_back(code);
    }
  }

  /// SYS / SCALE FACTOR: A1 system, I4 factor (1, 10, 100, 1000), I2 number of types
  /// (blank or 0: all of the system's), then the types, 12 a line (continued after 10X).
  void scale_factor(const std::string& line) {
    char sys = line.empty() ? ' ' : line[0];
    if (sys == ' ') {
      if (scale_continuing_ == 0) reader_.fail("SYS / SCALE FACTOR: continuation line without a system line before it");
      sys = scale_continuing_;
    } else {
      const int factor = with_context(reader_, fmt::format("SYS / SCALE FACTOR of '{}': factor (columns 3-6)", sys),
                                      [&] { return parse_int(column(line, 2, 4), "factor", 1, 1000); });
      if (factor != 1 && factor != 10 && factor != 100 && factor != 1000)
        reader_.fail(
            fmt::format("SYS / SCALE FACTOR of '{}': factor {} (columns 3-6) is not 1, 10, 100 or 1000", sys, factor));
      scale_ = factor;
      const std::string_view count = trim(column(line, 8, 2));
      scale_remaining_ =
          count.empty()
              ? 0
              : with_context(reader_, fmt::format("SYS / SCALE FACTOR of '{}': number of types (columns 9-10)", sys),
                             [&] { return parse_int(count, "number of types", 0, 99); });
      if (sys == 'G' && scale_remaining_ == 0) h_.gps_scale_all = scale_;
      if (sys == 'E' && scale_remaining_ == 0) h_.galileo_scale_all = scale_;
    }
    for (int k = 0; k < 12 && scale_remaining_ > 0; ++k, --scale_remaining_) {
      const std::string code(trim(column(line, 11 + 4 * static_cast<std::size_t>(k), 3)));
      if (code.size() != 3)
        reader_.fail(fmt::format(
            "SYS / SCALE FACTOR of '{}': type {} (columns {}-{}) is '{}', expected a 3-character code such as L1C", sys,
            k + 1, 12 + 4 * k, 14 + 4 * k, code));
      if (sys == 'G') h_.gps_scale[code] = scale_;
      if (sys == 'E') h_.galileo_scale[code] = scale_;
    }
    scale_continuing_ = scale_remaining_ > 0 ? sys : 0;
  }

  void interval(const std::string& line) {
    h_.interval_s = with_context(reader_, "INTERVAL (columns 1-10)", [&] { return parse_number(column(line, 0, 10)); });
    if (h_.interval_s && *h_.interval_s <= 0.0) h_.interval_s.reset();
    h_.interval_line = reader_.line_no();
  }

  void time_system(const std::string& line) {
    h_.time_system = std::string(trim(column(line, 48, 3)));
    h_.time_system_line = reader_.line_no();
  }

  /// LEAP SECONDS: I6 the current number; RINEX 3 adds, in columns 25-27, the system they
  /// count from (GPS, or BDS: BDT - UTC, 14 s less than GPS - UTC).
  void leap_seconds(const std::string& line) {
    const int n = with_context(reader_, "LEAP SECONDS: current number (columns 1-6)",
                               [&] { return parse_int(column(line, 0, 6), "leap seconds", -100, 100); });
    h_.leap_seconds = trim(column(line, 24, 3)) == "BDS" ? n + kBdtBehindGps_s : n;
  }

  void approx_position(const std::string& line) {
    Eigen::Vector3d r;
    for (int i = 0; i < 3; ++i) {
      const auto v = with_context(
          reader_, fmt::format("APPROX POSITION XYZ, {} (columns {}-{})", "XYZ"[i], 1 + 14 * i, 14 + 14 * i),
          [&] { return parse_number(column(line, 14 * static_cast<std::size_t>(i), 14)); });
      r(i) = v.value_or(0.0);
    }
    if (r.norm() > 1e6 && !h_.approx_position) h_.approx_position = r;
  }

  Header& h_;
  LineReader& reader_;
  char continuing_ = 0;  // the system whose type list goes on on the next line (RINEX 3)
  int remaining_ = 0;
  char scale_continuing_ = 0;
  int scale_remaining_ = 0;
  double scale_ = 1.0;
  int type_records_ = 0;
};

/// Seconds from the time system's tags to GPS time (TIME OF FIRST OBS, RINEX 2 and 3): GPS,
/// Galileo, QZSS and IRNSS system times run with GPS time (to within a microsecond); BDT
/// is 14 s behind; GLO tags are UTC, GPS time less the leap seconds, which only the LEAP
/// SECONDS record can give.
double seconds_to_gps(Header& h, const LineReader& reader) {
  if (h.time_system.empty()) {  // the default of a single-system file; a mixed file's is GPS
    static const std::map<char, std::string> defaults = {
        {'R', "GLO"}, {'E', "GAL"}, {'J', "QZS"}, {'C', "BDT"}, {'I', "IRN"}};
    const auto it = defaults.find(h.file_system);
    h.time_system = it == defaults.end() ? "GPS" : it->second;
  }
  const std::string& ts = h.time_system;
  if (ts == "GPS" || ts == "GAL" || ts == "QZS" || ts == "IRN") return 0.0;
  if (ts == "BDT") return kBdtBehindGps_s;
  if (ts == "GLO") {
    if (!h.leap_seconds)
      reader.fail(h.time_system_line,
                  "TIME OF FIRST OBS: time system GLO (UTC) needs the leap seconds to be put on GPS time, and the "
                  "header has no LEAP SECONDS record");
    return *h.leap_seconds;
  }
  reader.fail(h.time_system_line,
              fmt::format("TIME OF FIRST OBS: time system '{}' (columns 49-51) is not one of GPS, GAL, QZS, IRN, "
                          "BDT, GLO",
                          ts));
}

Header read_header(LineReader& reader) {
  Header h;
  std::string line;
  if (!reader.next(line)) reader.fail(1, "empty file, expected a RINEX observation file");
  if (label(line) != "RINEX VERSION / TYPE")
    reader.fail("not a RINEX file: expected 'RINEX VERSION / TYPE' in columns 61-80 of the first line");
  h.version = with_context(reader, "RINEX version (columns 1-9)", [&] {
    const auto v = parse_number(column(line, 0, 9));
    if (!v) throw std::invalid_argument("blank");
    return *v;
  });
  const bool v2 = h.version >= 2.095 && h.version < 2.115;
  const bool v3 = h.version >= 2.995 && h.version < 3.055;
  if (!v2 && !v3)
    reader.fail(fmt::format("unsupported RINEX version {:.2f} (supported: 2.10, 2.11, 3.00 to 3.05)", h.version));
  h.v2 = v2;
  const char type = line.size() > 20 ? line[20] : ' ';
  if (type != 'O') reader.fail(fmt::format("not an observation file: file type '{}' in column 21, expected 'O'", type));
  h.file_system = system_letter(line.size() > 40 ? line[40] : ' ');

  HeaderRecords records(h, reader);
  while (true) {
    if (!reader.next(line)) reader.fail(reader.line_no(), "no 'END OF HEADER' line: the header never ends");
    if (label(line) == "END OF HEADER") break;
    records.apply(line);
  }
  records.finish("the header");
  return h;
}

/// One 16-character observation field: value (F14.3), LLI digit, signal strength digit.
struct Field {
  std::optional<double> value;
  int lli = 0;
};

Field parse_field(const LineReader& reader, std::string_view line, std::size_t start, const std::string& what) {
  Field f;
  f.value = with_context(reader, what, [&] { return parse_number(column(line, start, 14)); });
  const std::string_view lli = column(line, start + 14, 1);
  if (!lli.empty() && lli[0] != ' ') {
    if (lli[0] < '0' || lli[0] > '9')
      reader.fail(fmt::format("{}: loss-of-lock indicator '{}' is not a digit", what, lli));
    f.lli = lli[0] - '0';
  }
  return f;
}

struct Parser {
  LineReader& reader;
  Header h;
  bool v2;
  ObservationFile out;
  double to_gps_s = 0.0;  ///< added to every epoch's tag: the file's time system to GPS time
  /// The lines of the last epoch kept (epoch line and records), to tell a repeat.
  std::vector<std::string> last_epoch_lines;

  GpsTime epoch_time(std::string_view line, bool rinex2) {
    CalendarTime c;
    if (rinex2) {
      const int yy = with_context(reader, "epoch year (columns 2-3)",
                                  [&] { return parse_int(column(line, 1, 2), "year", 0, 99); });
      c.year = yy < 80 ? 2000 + yy : 1900 + yy;
    } else {
      c.year = with_context(reader, "epoch year (columns 3-6)",
                            [&] { return parse_int(column(line, 2, 4), "year", 1980, 2200); });
    }
    const std::size_t o = rinex2 ? 4 : 7;  // month's column (0-based)
    c.month = with_context(reader, fmt::format("epoch month (columns {}-{})", o + 1, o + 2),
                           [&] { return parse_int(column(line, o, 2), "month", 1, 12); });
    c.day = with_context(reader, fmt::format("epoch day (columns {}-{})", o + 4, o + 5),
                         [&] { return parse_int(column(line, o + 3, 2), "day", 1, 31); });
    c.hour = with_context(reader, fmt::format("epoch hour (columns {}-{})", o + 7, o + 8),
                          [&] { return parse_int(column(line, o + 6, 2), "hour", 0, 23); });
    c.minute = with_context(reader, fmt::format("epoch minute (columns {}-{})", o + 10, o + 11),
                            [&] { return parse_int(column(line, o + 9, 2), "minute", 0, 59); });
    c.second = with_context(reader, fmt::format("epoch second (columns {}-{})", o + 12, o + 22), [&] {
      const auto s = parse_number(column(line, o + 11, 11));
      if (!s || *s < 0.0 || *s >= 61.0) throw std::invalid_argument("expected seconds in [0, 61)");
      return *s;
    });
    return gps_time_from_calendar(c);
  }

  /// What a type's stored values are divided by (SYS / SCALE FACTOR; 1 without one).
  double scale_of(char sys, const std::string& type) const {
    const auto& scale = sys == 'E' ? h.galileo_scale : h.gps_scale;
    const auto it = scale.find(type);
    return it != scale.end() ? it->second : (sys == 'E' ? h.galileo_scale_all : h.gps_scale_all).value_or(1.0);
  }

  /// Reads one satellite's observations from `text` (all its fields in one string) and
  /// files it: GPS L1 C/A and Galileo E1 kept, the rest counted.
  void take_satellite(std::string_view sat, const std::string& text, int line_no, ObservationEpoch& epoch, bool keep) {
    const char sys = system_letter(sat[0]);
    const bool galileo = sys == 'E' && h.reads_galileo();
    if (sys != 'G' && !galileo) {
      if (keep) ++out.report.skipped_satellite_records[std::string(1, sys)];
      return;
    }
    const int prn = with_context(reader, fmt::format("satellite '{}' number", sat), [&] {
      return galileo ? parse_int(sat.substr(1), "SVID", 1, 36) : parse_int(sat.substr(1), "PRN", 1, 32);
    });
    const GpsTypes& types = galileo ? h.galileo : h.gps;
    GpsL1Observation o;
    o.prn = prn;
    bool lost = false;
    for (std::size_t k = 0; k < types.all.size(); ++k) {
      const std::string what =
          fmt::format("{}{:02d} {} (line {} columns {}-{})", sys, prn, types.all[k], line_no,
                      (v2 ? 1 + 16 * (k % 5) : 4 + 16 * k), (v2 ? 14 + 16 * (k % 5) : 17 + 16 * k));
      Field f = parse_field(reader, text, 16 * k, what);
      if (f.value) *f.value /= scale_of(sys, types.all[k]);
      const int i = static_cast<int>(k);
      if (i == types.pseudorange) o.pseudorange_m = f.value;
      else if (i == types.phase) o.carrier_phase_cycles = f.value;
      else if (i == types.doppler) o.doppler_hz = f.value;
      else if (i == types.cn0) o.cn0_dbhz = f.value;
      else {
        if (f.value && keep)
          ++(galileo ? out.report.skipped_galileo_values : out.report.skipped_gps_values)[types.all[k]];
        continue;
      }
      if (f.value && (f.lli & 1)) lost = true;
    }
    if (!keep) return;
    if (!o.pseudorange_m && !o.carrier_phase_cycles && !o.doppler_hz) return;  // no L1 C/A signal (only other bands)
    o.loss_of_lock = lost || epoch.flag == 1;
    ObservationReport& r = out.report;
    ++(galileo ? r.galileo_satellite_records : r.gps_satellite_records);
    r.missing_pseudorange += !o.pseudorange_m;
    r.missing_phase += !o.carrier_phase_cycles;
    r.missing_doppler += !o.doppler_hz;
    r.missing_cn0 += !o.cn0_dbhz;
    r.loss_of_lock += o.loss_of_lock;
    (galileo ? epoch.galileo : epoch.gps).push_back(o);
  }

  /// The satellite records of an epoch (flag 0, 1 or 6). RINEX 3: one line per satellite
  /// starting with its ID. RINEX 2: the IDs in the epoch line(s), then each satellite's
  /// fields five to a line.
  void read_records(int count, const std::vector<std::string>& v2_ids, ObservationEpoch& epoch, bool keep) {
    for (int s = 0; s < count; ++s) {
      if (!v2) {
        const std::string line =
            reader.require(fmt::format("satellite record {} of {} of the epoch at line {}", s + 1, count, epoch.line));
        if (line.size() < 3 || line[0] == '>')
          reader.fail(
              fmt::format("satellite record {} of {} of the epoch at line {} expected, got '{}' (truncated epoch?)",
                          s + 1, count, epoch.line, line.substr(0, 20)));
        const std::string text = line.size() > 3 ? line.substr(3) : std::string();
        const int n = h.type_counts.count(system_letter(line[0])) ? h.type_counts[system_letter(line[0])] : 0;
        if (system_letter(line[0]) == 'G' || n > 0)
          take_satellite(std::string_view(line).substr(0, 3), text, reader.line_no(), epoch, keep);
        else if (keep) ++out.report.skipped_satellite_records[std::string(1, line[0])];
      } else {
        const std::size_t lines = (h.gps.all.size() + 4) / 5;
        std::string text;
        int first_line = 0;
        for (std::size_t l = 0; l < lines; ++l) {
          std::string line =
              reader.require(fmt::format("observations of satellite '{}' (record {} of {} of the epoch at line {})",
                                         v2_ids[static_cast<std::size_t>(s)], s + 1, count, epoch.line));
          if (l == 0) first_line = reader.line_no();
          line.resize(80, ' ');
          text += line;
        }
        take_satellite(v2_ids[static_cast<std::size_t>(s)], text, first_line, epoch, keep);
      }
    }
  }

  /// RINEX 2: the satellite IDs of an epoch, 12 per line from column 33.
  std::vector<std::string> v2_satellites(const std::string& first, int count) {
    std::vector<std::string> ids;
    std::string line = first;
    for (int s = 0; s < count; ++s) {
      if (s > 0 && s % 12 == 0) line = reader.require("continuation of the epoch's satellite list");
      std::string id(column(line, 32 + 3 * static_cast<std::size_t>(s % 12), 3));
      if (id.size() != 3 || trim(id).empty())
        reader.fail(fmt::format("epoch satellite list: satellite {} of {} (columns {}-{}) is missing", s + 1, count,
                                33 + 3 * (s % 12), 35 + 3 * (s % 12)));
      ids.push_back(id);
    }
    return ids;
  }

  /// An event (flags 2-5) and its special records: header records, which apply from here
  /// on (new observation types, scale factors), or comments.
  void event(int flag, int count) {
    ++out.report.event_epochs;
    const int event_line = reader.line_no();
    HeaderRecords records(h, reader);
    for (int k = 0; k < count; ++k) {
      const std::string line = reader.require(
          fmt::format("special record {} of {} of the event (flag {}) at line {}", k + 1, count, flag, event_line));
      if (!v2 && !line.empty() && line[0] == '>')
        reader.fail(
            fmt::format("special record {} of {} of the event (flag {}) at line {} expected, got an epoch "
                        "line (the event's record count is wrong)",
                        k + 1, count, flag, event_line));
      records.apply(line);
    }
    records.finish(fmt::format("the event at line {}", event_line));
    out.report.observation_type_changes += records.type_records();
  }

  /// Files an epoch read whole (`lines`: its epoch line and records): a repeat of the last
  /// one, record for record, is skipped and counted; any other epoch not after it is an error.
  void file_epoch(ObservationEpoch epoch, std::vector<std::string> lines, const ObservationReport& before) {
    if (!out.epochs.empty()) {
      const double dt = epoch.t.seconds_since(out.epochs.back().t);
      if (dt == 0.0 && lines == last_epoch_lines) {
        out.report = before;  // its records were counted as they were read
        if (out.report.repeated_epochs++ == 0) out.report.first_repeated_epoch_line = epoch.line;
        return;
      }
      if (dt <= 0.0)
        reader.fail(epoch.line, fmt::format("epoch time {} goes {} the epoch at line {} (epochs must increase)",
                                            fmt::format("{} {:.7f}", epoch.t.week, epoch.t.sow),
                                            dt == 0.0 ? "no further than (with other records)" : "back before",
                                            out.epochs.back().line));
    }
    out.report.power_failure_epochs += epoch.flag == 1;
    last_epoch_lines = std::move(lines);
    out.epochs.push_back(std::move(epoch));
  }

  void run() {
    std::string line;
    while (reader.next(line)) {
      if (trim(line).empty()) continue;
      if (!v2 && line[0] != '>')
        reader.fail(fmt::format("expected an epoch record starting with '>', got '{}'", line.substr(0, 20)));
      const std::size_t flag_col = v2 ? 28 : 31;
      const int flag = with_context(reader, fmt::format("epoch flag (column {})", flag_col + 1),
                                    [&] { return parse_int(column(line, flag_col, 1), "epoch flag", 0, 6); });
      const int count =
          with_context(reader, fmt::format("number of satellites (columns {}-{})", flag_col + 2, flag_col + 4),
                       [&] { return parse_int(column(line, flag_col + 1, 3), "number of satellites", 0, 999); });
      if (flag >= 2 && flag <= 5) {
        event(flag, count);
        continue;
      }
      ObservationEpoch epoch;
      epoch.line = reader.line_no();
      epoch.flag = flag;
      epoch.t = epoch_time(line, v2).plus_seconds(to_gps_s);
      const auto clock =
          with_context(reader, v2 ? "receiver clock offset (columns 69-80)" : "receiver clock offset (columns 42-56)",
                       [&] { return parse_number(v2 ? column(line, 68, 12) : column(line, 41, 15)); });
      epoch.receiver_clock_offset_s = clock;
      std::vector<std::string> lines{line};
      reader.capture_into(&lines);
      const std::vector<std::string> ids = v2 ? v2_satellites(line, count) : std::vector<std::string>{};
      if (flag == 6) {  // cycle slip records: in the observation format, not observations
        ++out.report.cycle_slip_epochs;
        read_records(count, ids, epoch, false);
        reader.capture_into(nullptr);
        continue;
      }
      // Only an epoch at the last one's time can be a repeat, whose counts are undone.
      const bool may_repeat = !out.epochs.empty() && epoch.t.seconds_since(out.epochs.back().t) == 0.0;
      const ObservationReport before = may_repeat ? out.report : ObservationReport{};
      read_records(count, ids, epoch, true);
      reader.capture_into(nullptr);
      file_epoch(std::move(epoch), std::move(lines), before);
    }
  }
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// The epochs' own spacing (their median interval) is the nominal interval; a header
/// INTERVAL that disagrees is reported, and used only where the data have no interval.
void find_gaps(ObservationFile& f, const Header& h, const std::string& name) {
  std::vector<double> dts;
  for (std::size_t i = 1; i < f.epochs.size(); ++i) dts.push_back(f.epochs[i].t.seconds_since(f.epochs[i - 1].t));
  ObservationReport& r = f.report;
  r.header_interval_s = h.interval_s;
  r.nominal_interval_s = dts.empty() ? h.interval_s.value_or(0.0) : median(dts);
  if (h.interval_s && !dts.empty() && std::abs(*h.interval_s - r.nominal_interval_s) > 1e-3 * r.nominal_interval_s)
    r.warnings.push_back(fmt::format(
        "{}:{}: INTERVAL says {:g} s, but the epochs are {:g} s apart (the median of {} intervals): the data's "
        "spacing is used",
        name, h.interval_line, *h.interval_s, r.nominal_interval_s, dts.size()));
  if (r.nominal_interval_s <= 0.0) return;
  for (std::size_t i = 1; i < f.epochs.size(); ++i) {
    const double dt = dts[i - 1];
    if (dt <= 1.5 * r.nominal_interval_s) continue;
    f.epochs[i].after_gap = true;
    r.gaps.push_back({f.epochs[i].line, f.epochs[i - 1].t, f.epochs[i].t, dt});
  }
}

/// Receiver clock re-settings: the median over common satellites of the pseudorange
/// change minus what the Dopplers predict for it. Between consecutive epochs (no gap) the
/// Dopplers take the motion and the clock drift, and what is left is code noise and
/// multipath, a metre or two at most (the walk_0827 recording: 1.0 m); a common step beyond
/// kMinStepConsecutive_m is a re-set, whether by whole milliseconds (u-blox and most
/// receivers) or by microseconds (a receiver adjusting its time tags, as deepnav's own does:
/// steps of about 1 km). Across a gap the Dopplers' mean misses the motion in between, and
/// only a step beyond 1/10 ms of range (30 km) counts.
constexpr double kMinStepConsecutive_m = 100.0;

void find_clock_jumps(ObservationFile& f) {
  for (std::size_t i = 1; i < f.epochs.size(); ++i) {
    const ObservationEpoch& a = f.epochs[i - 1];
    ObservationEpoch& b = f.epochs[i];
    const double dt = b.t.seconds_since(a.t);
    std::vector<double> steps;
    for (const GpsL1Observation& ob : b.gps) {
      const auto it =
          std::find_if(a.gps.begin(), a.gps.end(), [&](const GpsL1Observation& o) { return o.prn == ob.prn; });
      if (it == a.gps.end() || !it->pseudorange_m || !ob.pseudorange_m) continue;
      double predicted = 0.0;
      if (it->doppler_hz && ob.doppler_hz)
        predicted = -gps::kL1Wavelength_m * 0.5 * (*it->doppler_hz + *ob.doppler_hz) * dt;
      steps.push_back(*ob.pseudorange_m - *it->pseudorange_m - predicted);
    }
    if (steps.empty()) continue;
    const double step = median(steps);
    const bool consecutive = f.report.nominal_interval_s > 0.0 && dt <= 1.5 * f.report.nominal_interval_s;
    if (std::abs(step) < (consecutive ? kMinStepConsecutive_m : 0.1 * kMillisecondRange_m)) continue;
    b.clock_jump_m = step;
    f.report.clock_jumps.push_back({b.line, b.t, step, step / kMillisecondRange_m});
  }
}

}  // namespace

ObservationFile read_rinex_obs(std::istream& in, const std::string& name) {
  LineReader reader(in, name);
  Parser p{reader, read_header(reader), false, {}, 0.0, {}};
  p.v2 = p.h.v2;
  p.to_gps_s = seconds_to_gps(p.h, reader);
  ObservationReport& r = p.out.report;
  r.version = p.h.version;
  r.approx_position_ecef_m = p.h.approx_position;
  r.time_system = p.h.time_system;
  p.run();
  if (p.out.epochs.empty()) reader.fail(reader.line_no(), "no observation epochs after the header");
  r.epochs = static_cast<int>(p.out.epochs.size());
  if (r.repeated_epochs > 0)
    r.warnings.push_back(fmt::format("{}:{}: {} epoch(s) repeat the epoch before them record for record: skipped", name,
                                     r.first_repeated_epoch_line, r.repeated_epochs));
  find_gaps(p.out, p.h, name);
  find_clock_jumps(p.out);
  return std::move(p.out);
}

ObservationFile read_rinex_obs(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open RINEX observation file '" + path + "'");
  return read_rinex_obs(in, path);
}

}  // namespace deepnav
