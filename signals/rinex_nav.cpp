#include "signals/rinex_nav.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <istream>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string_view>

#include "ins/input_file.hpp"
#include "signals/galileo/galileo_constants.hpp"
#include "signals/galileo/inav_words.hpp"
#include "signals/gps_constants.hpp"
#include "signals/lnav_message.hpp"
#include "signals/rinex_fields.hpp"

namespace deepnav {

namespace {

constexpr int kOrbitLines = 7;              // broadcast orbit lines of a GPS record
constexpr double kUnknownTransmit = 9.0e8;  // RINEX writes 0.9999E+09 for "not known"

// ---------------------------------------------------------------------------
// Fixed-column fields

using rinex::column;
using rinex::parse_number;
using rinex::trim;

/// Whole number within [lo, hi]; `what` names the quantity for the message.
int to_int(double value, const char* what, int lo, int hi) {
  const double r = std::round(value);
  if (std::abs(value - r) > 1e-6 || r < lo || r > hi) {
    throw std::invalid_argument(fmt::format("expected {} as a whole number in [{}, {}], got {}", what, lo, hi, value));
  }
  return static_cast<int>(r);
}

// ---------------------------------------------------------------------------
// Line-numbered input with errors that name file and line

class LineReader {
 public:
  LineReader(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++line_no_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
  /// Next line that is not entirely blank.
  bool next_nonblank(std::string& line) {
    while (next(line)) {
      if (!trim(line).empty()) return true;
    }
    return false;
  }
  int line_no() const { return line_no_; }
  const std::string& name() const { return name_; }

  [[noreturn]] void fail(int line_no, const std::string& message) const {
    throw std::runtime_error(fmt::format("{}:{}: {}", name_, line_no, message));
  }
  [[noreturn]] void fail(const std::string& message) const { fail(line_no_, message); }

 private:
  std::istream& in_;
  std::string name_;
  int line_no_ = 0;
};

/// Runs `parse` and turns its bare invalid_argument into a file:line error with `context`.
template <typename F>
auto with_context(const LineReader& reader, const std::string& context, F&& parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    reader.fail(fmt::format("{}: {}", context, e.what()));
  }
}

// ---------------------------------------------------------------------------
// Header

struct Header {
  double version = 0.0;
  bool has_alpha = false, has_beta = false;
};

std::string_view header_label(std::string_view line) { return trim(column(line, 60, 20)); }

void read_version_line(LineReader& reader, Header& header) {
  std::string line;
  if (!reader.next(line)) reader.fail(0, "empty file, expected a RINEX navigation file");
  if (header_label(line) != "RINEX VERSION / TYPE") {
    reader.fail("not a RINEX file: expected 'RINEX VERSION / TYPE' in columns 61-80 of the first line");
  }
  header.version = with_context(reader, "RINEX version (columns 1-9)", [&] {
    const auto v = parse_number(column(line, 0, 9));
    if (!v) throw std::invalid_argument("expected a number, got a blank field");
    return *v;
  });
  if (header.version < 2.0 || header.version >= 4.0) {
    reader.fail(fmt::format("unsupported RINEX version {:.2f} (supported: 2.10, 2.11, 3.0x)", header.version));
  }
  const char type = line.size() > 20 ? line[20] : ' ';
  if (type != 'N') {
    reader.fail(fmt::format("not a GPS navigation file: file type '{}' in column 21, expected 'N'", type));
  }
}

std::array<double, 4> four_numbers(const LineReader& reader, std::string_view line, std::size_t start,
                                   std::size_t width, const char* what) {
  std::array<double, 4> out{};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto v = with_context(reader, what, [&] { return parse_number(column(line, start + i * width, width)); });
    if (!v) reader.fail(fmt::format("expected 4 numbers in {}, got '{}'", what, line));
    out[i] = *v;
  }
  return out;
}

int header_int(const LineReader& reader, std::string_view line, std::size_t start, std::size_t width, const char* what,
               int lo, int hi) {
  return with_context(reader, what, [&] {
    const auto v = parse_number(column(line, start, width));
    if (!v) throw std::invalid_argument("expected a number, got a blank field");
    return to_int(*v, what, lo, hi);
  });
}

double header_double(const LineReader& reader, std::string_view line, std::size_t start, std::size_t width,
                     const char* what) {
  return with_context(reader, what, [&] {
    const auto v = parse_number(column(line, start, width));
    if (!v) throw std::invalid_argument("expected a number, got a blank field");
    return *v;
  });
}

void read_leap_seconds(const LineReader& reader, std::string_view line, NavData& nav) {
  nav.utc.delta_t_ls = header_int(reader, line, 0, 6, "LEAP SECONDS", -1000, 1000);
  nav.leap_seconds_valid = true;
  // RINEX 3 adds the future leap second, its week and day; optional.
  if (!trim(column(line, 6, 18)).empty()) {
    nav.utc.delta_t_lsf = header_int(reader, line, 6, 6, "LEAP SECONDS future value", -1000, 1000);
    nav.utc.wn_lsf = header_int(reader, line, 12, 6, "LEAP SECONDS week", 0, 100000);
    nav.utc.dn = header_int(reader, line, 18, 6, "LEAP SECONDS day", 0, 7);
  }
}

/// A header value (ionosphere, UTC) against its LNAV field; the error names the line.
void check_header_field(const LineReader& reader, const char* label, const char* field, double value) {
  const lnav::FieldLimits lim = lnav::field_limits(field);
  const double slack = (lim.max - lim.min) * 0x1p-32;  // one LSB: 12 digits may round full scale up
  if (value >= lim.min - slack && value <= lim.max + slack) return;
  reader.fail(
      fmt::format("{}: {} = {:g} is outside [{:.6g}, {:.6g}], the range a GPS satellite can broadcast "
                  "(IS-GPS-200 LNAV field): a corrupt navigation file",
                  label, field, value, lim.min, lim.max));
}

std::array<double, 4> iono_numbers(const LineReader& reader, std::string_view line, std::size_t start,
                                   const char* label, bool alpha) {
  static constexpr const char* kAlpha[] = {"alpha0", "alpha1", "alpha2", "alpha3"};
  static constexpr const char* kBeta[] = {"beta0", "beta1", "beta2", "beta3"};
  const std::array<double, 4> v = four_numbers(reader, line, start, 12, label);
  for (std::size_t i = 0; i < 4; ++i) check_header_field(reader, label, alpha ? kAlpha[i] : kBeta[i], v[i]);
  return v;
}

void read_header_line_v2(const LineReader& reader, std::string_view line, std::string_view label, NavData& nav,
                         Header& header) {
  if (label == "ION ALPHA") {
    nav.iono.alpha = iono_numbers(reader, line, 2, "ION ALPHA", true);
    header.has_alpha = true;
  } else if (label == "ION BETA") {
    nav.iono.beta = iono_numbers(reader, line, 2, "ION BETA", false);
    header.has_beta = true;
  } else if (label == "DELTA-UTC: A0,A1,T,W") {
    nav.utc.a0_s = header_double(reader, line, 3, 19, "DELTA-UTC A0");
    nav.utc.a1_sps = header_double(reader, line, 22, 19, "DELTA-UTC A1");
    check_header_field(reader, "DELTA-UTC", "A0", nav.utc.a0_s);
    check_header_field(reader, "DELTA-UTC", "A1", nav.utc.a1_sps);
    nav.utc.tot_s = header_int(reader, line, 41, 9, "DELTA-UTC T", 0, 604800);
    nav.utc.wnt = header_int(reader, line, 50, 9, "DELTA-UTC W", 0, 100000);
    nav.utc.valid = true;
  } else if (label == "LEAP SECONDS") {
    read_leap_seconds(reader, line, nav);
  }
}

/// A header value against the range [lo, hi] its Galileo message field can carry; the error
/// names the line.
void check_galileo_header_field(const LineReader& reader, const char* label, const char* field, double value, double lo,
                                double hi) {
  if (value >= lo && value <= hi) return;
  reader.fail(
      fmt::format("{}: {} = {:g} is outside [{:.6g}, {:.6g}], the range a Galileo satellite can broadcast "
                  "(OS SIS ICD message field): a corrupt navigation file",
                  label, field, value, lo, hi));
}

/// The same for a signed field of `bits` bits with LSB `lsb`.
void check_galileo_header_field(const LineReader& reader, const char* label, const char* field, double value, int bits,
                                double lsb) {
  const double half_range = std::ldexp(lsb, bits - 1);
  check_galileo_header_field(reader, label, field, value, -half_range, half_range - lsb);
}

/// RINEX 3's Galileo header lines: NeQuick G coefficients, GST-GPST and GST-UTC. Their weeks
/// are RINEX's continuous ones (GPS numbering) and are kept as GST weeks.
void read_galileo_header_line(const LineReader& reader, std::string_view line, std::string_view label,
                              std::string_view kind, NavData& nav) {
  if (label == "IONOSPHERIC CORR" && kind == "GAL") {
    const std::array<double, 4> ai = four_numbers(reader, line, 5, 12, "IONOSPHERIC CORR GAL");
    // a_i0: 11 bits of 1/4 sfu; a_i1: signed 11 bits of 2^-8; a_i2: signed 14 bits of 2^-15.
    check_galileo_header_field(reader, "IONOSPHERIC CORR GAL", "a_i0", ai[0], 0.0, 2047 * 0x1p-2);
    check_galileo_header_field(reader, "IONOSPHERIC CORR GAL", "a_i1", ai[1], 11, 0x1p-8);
    check_galileo_header_field(reader, "IONOSPHERIC CORR GAL", "a_i2", ai[2], 14, 0x1p-15);
    nav.galileo_iono.ai0_sfu = ai[0];
    nav.galileo_iono.ai1_sfu_per_deg = ai[1];
    nav.galileo_iono.ai2_sfu_per_deg2 = ai[2];
    nav.galileo_iono.valid = true;
  } else if (label == "TIME SYSTEM CORR" && kind == "GAGP") {
    nav.ggto.a0g_s = header_double(reader, line, 5, 17, "TIME SYSTEM CORR GAGP a0");
    nav.ggto.a1g_sps = header_double(reader, line, 22, 16, "TIME SYSTEM CORR GAGP a1");
    check_galileo_header_field(reader, "TIME SYSTEM CORR GAGP", "A0G", nav.ggto.a0g_s, 16, 0x1p-35);
    check_galileo_header_field(reader, "TIME SYSTEM CORR GAGP", "A1G", nav.ggto.a1g_sps, 12, 0x1p-51);
    nav.ggto.t0g_s = header_int(reader, line, 38, 7, "TIME SYSTEM CORR GAGP T", 0, 604800);
    nav.ggto.wn0g = header_int(reader, line, 45, 5, "TIME SYSTEM CORR GAGP W", galileo::kGstWeekOffsetFromGps, 100000) -
                    galileo::kGstWeekOffsetFromGps;
    nav.ggto.valid = true;
  } else if (label == "TIME SYSTEM CORR" && kind == "GAUT") {
    nav.galileo_utc.a0_s = header_double(reader, line, 5, 17, "TIME SYSTEM CORR GAUT a0");
    nav.galileo_utc.a1_sps = header_double(reader, line, 22, 16, "TIME SYSTEM CORR GAUT a1");
    check_galileo_header_field(reader, "TIME SYSTEM CORR GAUT", "A0", nav.galileo_utc.a0_s, 32, 0x1p-30);
    check_galileo_header_field(reader, "TIME SYSTEM CORR GAUT", "A1", nav.galileo_utc.a1_sps, 24, 0x1p-50);
    nav.galileo_utc.tot_s = header_int(reader, line, 38, 7, "TIME SYSTEM CORR GAUT T", 0, 604800);
    nav.galileo_utc.wnt =
        header_int(reader, line, 45, 5, "TIME SYSTEM CORR GAUT W", galileo::kGstWeekOffsetFromGps, 100000) -
        galileo::kGstWeekOffsetFromGps;
    nav.galileo_utc.valid = true;
  }
}

void read_header_line_v3(const LineReader& reader, std::string_view line, std::string_view label, NavData& nav,
                         Header& header) {
  const std::string_view kind = trim(column(line, 0, 4));
  if (label == "IONOSPHERIC CORR" && kind == "GPSA") {
    nav.iono.alpha = iono_numbers(reader, line, 5, "IONOSPHERIC CORR GPSA", true);
    header.has_alpha = true;
  } else if (label == "IONOSPHERIC CORR" && kind == "GPSB") {
    nav.iono.beta = iono_numbers(reader, line, 5, "IONOSPHERIC CORR GPSB", false);
    header.has_beta = true;
  } else if (label == "TIME SYSTEM CORR" && kind == "GPUT") {
    nav.utc.a0_s = header_double(reader, line, 5, 17, "TIME SYSTEM CORR GPUT a0");
    nav.utc.a1_sps = header_double(reader, line, 22, 16, "TIME SYSTEM CORR GPUT a1");
    check_header_field(reader, "TIME SYSTEM CORR GPUT", "A0", nav.utc.a0_s);
    check_header_field(reader, "TIME SYSTEM CORR GPUT", "A1", nav.utc.a1_sps);
    nav.utc.tot_s = header_int(reader, line, 38, 7, "TIME SYSTEM CORR GPUT T", 0, 604800);
    nav.utc.wnt = header_int(reader, line, 45, 5, "TIME SYSTEM CORR GPUT W", 0, 100000);
    nav.utc.valid = true;
  } else if (label == "LEAP SECONDS") {
    read_leap_seconds(reader, line, nav);
  } else {
    read_galileo_header_line(reader, line, label, kind, nav);
  }
}

Header read_header(LineReader& reader, NavData& nav) {
  Header header;
  read_version_line(reader, header);
  nav.rinex_version = header.version;
  std::string line;
  while (reader.next(line)) {
    const std::string_view label = header_label(line);
    if (label == "END OF HEADER") {
      nav.iono.valid = header.has_alpha && header.has_beta;
      return header;
    }
    // A data record where a header line should be: numbers in the label columns.
    bool numeric_label = false;
    try {
      numeric_label = parse_number(label).has_value();
    } catch (const std::invalid_argument&) {
    }
    if (numeric_label) reader.fail("expected END OF HEADER before the first record");
    if (header.version < 3.0) {
      read_header_line_v2(reader, line, label, nav, header);
    } else {
      read_header_line_v3(reader, line, label, nav, header);
    }
  }
  reader.fail("no END OF HEADER line before the end of the file");
}

// ---------------------------------------------------------------------------
// Records

struct Layout {
  std::size_t epoch_numbers_col;  // first clock field on the epoch line
  std::size_t orbit_col;          // first field on a broadcast orbit line
};

Layout layout_for(double version) { return version < 3.0 ? Layout{22, 3} : Layout{23, 4}; }

/// Epoch fields (columns are 0-based). RINEX 2: I2 PRN, I2.2 year, 4 x I3, F5.1 seconds;
/// RINEX 3: A1 I2.2, I5 year, 5 x I3.
struct EpochLine {
  int prn;
  CalendarTime toc;
  std::array<double, 3> clock;
};

EpochLine parse_epoch_line(const LineReader& reader, std::string_view line, double version, int max_prn) {
  EpochLine ep{};
  const bool v2 = version < 3.0;
  auto whole = [&](std::size_t start, std::size_t width, const char* what, int lo, int hi) {
    return with_context(reader, fmt::format("epoch line, {} (columns {}-{})", what, start + 1, start + width), [&] {
      const auto v = parse_number(column(line, start, width));
      if (!v) throw std::invalid_argument("expected a number, got a blank field");
      return to_int(*v, what, lo, hi);
    });
  };
  ep.prn = v2 ? whole(0, 2, "PRN", 1, max_prn) : whole(1, 2, "PRN", 1, max_prn);
  if (v2) {
    const int yy = whole(2, 3, "year", 0, 99);
    ep.toc.year = yy < 80 ? 2000 + yy : 1900 + yy;
  } else {
    ep.toc.year = whole(3, 5, "year", 1980, 2200);
  }
  const std::size_t base = v2 ? 5 : 8;
  ep.toc.month = whole(base, 3, "month", 1, 12);
  ep.toc.day = whole(base + 3, 3, "day", 1, 31);
  ep.toc.hour = whole(base + 6, 3, "hour", 0, 23);
  ep.toc.minute = whole(base + 9, 3, "minute", 0, 59);
  ep.toc.second = with_context(reader, "epoch line, seconds", [&] {
    const auto v = parse_number(v2 ? column(line, 17, 5) : column(line, 20, 3));
    if (!v || *v < 0.0 || *v >= 61.0) throw std::invalid_argument("expected seconds in [0, 61)");
    return *v;
  });
  if (ep.toc.day > days_in_month(ep.toc.year, ep.toc.month)) {
    reader.fail(
        fmt::format("epoch line, day (columns {}-{}): {:04d}-{:02d}-{:02d} is not a date ({:04d}-{:02d} has {} days)",
                    base + 4, base + 6, ep.toc.year, ep.toc.month, ep.toc.day, ep.toc.year, ep.toc.month,
                    days_in_month(ep.toc.year, ep.toc.month)));
  }
  const Layout lay = layout_for(version);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto v = with_context(reader, fmt::format("epoch line, clock field {}", i + 1),
                                [&] { return parse_number(column(line, lay.epoch_numbers_col + 19 * i, 19)); });
    if (!v) reader.fail(fmt::format("expected 3 clock numbers on the epoch line, got '{}'", line));
    ep.clock[i] = *v;
  }
  return ep;
}

/// Reads broadcast orbit line `index` (1-based) and returns its fields; `required` of them
/// must be present, absent optional ones are 0.
std::array<double, 4> read_orbit_line(LineReader& reader, double version, int index, int required, int prn,
                                      int record_line) {
  std::string line;
  const Layout lay = layout_for(version);
  if (!reader.next(line)) {
    reader.fail(record_line, fmt::format("record of PRN {} is truncated: the file ends before broadcast orbit line {} "
                                         "(expected {} lines)",
                                         prn, index, kOrbitLines));
  }
  // Continuation lines start with blanks; anything else is the next record.
  if (!trim(column(line, 0, lay.orbit_col)).empty()) {
    reader.fail(fmt::format("record of PRN {} (line {}) is truncated: expected broadcast orbit line {}, got '{}'", prn,
                            record_line, index, line));
  }
  std::array<double, 4> out{};
  int present = 0;
  for (int i = 0; i < 4; ++i) {
    const auto v = with_context(reader, fmt::format("broadcast orbit line {}, field {}", index, i + 1), [&] {
      return parse_number(column(line, lay.orbit_col + 19 * static_cast<std::size_t>(i), 19));
    });
    if (v) {
      out[static_cast<std::size_t>(i)] = *v;
      if (present == i) ++present;  // counts the leading run of present fields
    }
  }
  if (present < required) {
    reader.fail(fmt::format("expected {} numbers in broadcast orbit line {}, got '{}'", required, index, line));
  }
  return out;
}

/// A broadcast value of a record with where it stands: the record's line offset (0: the
/// epoch line, i: broadcast orbit line i) and field (1-based), and its LNAV field name.
struct BroadcastValue {
  const char* name;
  int line_offset;
  int field;
  double value;
  const char* unit;
};

/// Checks every broadcast value of a record against what its LNAV field can carry (the
/// range every real broadcast lies in, IS-GPS-200 Tables 20-I and 20-III); angles may come
/// in any normalisation, so they need only lie within one turn either way. A value outside
/// (a corrupt file: af0 = 1e300, Cuc = 1e29) is an error naming the line, satellite and field.
void check_broadcast_ranges(const LineReader& reader, int record_line, int prn, const Ephemeris& e) {
  constexpr double kTurn = 2.0 * gps::kPi;
  const BroadcastValue values[] = {{"af0", 0, 1, e.af0_s, "s"},
                                   {"af1", 0, 2, e.af1_sps, "s/s"},
                                   {"af2", 0, 3, e.af2_sps2, "s/s^2"},
                                   {"Crs", 1, 2, e.crs_m, "m"},
                                   {"delta n", 1, 3, e.delta_n_radps, "rad/s"},
                                   {"M0", 1, 4, e.m0_rad, "rad"},
                                   {"Cuc", 2, 1, e.cuc_rad, "rad"},
                                   {"e", 2, 2, e.e, ""},
                                   {"Cus", 2, 3, e.cus_rad, "rad"},
                                   {"sqrt A", 2, 4, e.sqrt_a, "sqrt(m)"},
                                   {"Cic", 3, 2, e.cic_rad, "rad"},
                                   {"OMEGA0", 3, 3, e.omega0_rad, "rad"},
                                   {"Cis", 3, 4, e.cis_rad, "rad"},
                                   {"i0", 4, 1, e.i0_rad, "rad"},
                                   {"Crc", 4, 2, e.crc_m, "m"},
                                   {"omega", 4, 3, e.omega_rad, "rad"},
                                   {"OMEGADOT", 4, 4, e.omega_dot_radps, "rad/s"},
                                   {"IDOT", 5, 1, e.idot_radps, "rad/s"},
                                   {"TGD", 6, 3, e.tgd_s, "s"}};
  for (const BroadcastValue& v : values) {
    lnav::FieldLimits lim = lnav::field_limits(v.name);
    const std::string_view name(v.name);
    if (name == "M0" || name == "OMEGA0" || name == "omega" || name == "i0") lim = {-kTurn, kTurn};
    // One LSB of slack either way: a file's 12 digits may round a full-scale value up.
    const double slack = (lim.max - lim.min) * 0x1p-32;
    if (v.value >= lim.min - slack && v.value <= lim.max + slack) continue;
    const std::string where = v.line_offset == 0
                                  ? fmt::format("epoch line, clock field {}", v.field)
                                  : fmt::format("broadcast orbit line {}, field {}", v.line_offset, v.field);
    reader.fail(record_line + v.line_offset,
                fmt::format("PRN {} (record at line {}), {}: {} = {:g} {} is outside [{:.6g}, {:.6g}], the range a GPS "
                            "satellite can broadcast (IS-GPS-200 LNAV field): a corrupt navigation file",
                            prn, record_line, where, v.name, v.value, v.unit, lim.min, lim.max));
  }
  // sqrt(A) within what LNAV carries may still put the orbit inside the Earth.
  constexpr double kMinSqrtA = 2525.0;  // sqrt of the Earth's equatorial radius, 6378137 m
  if (e.sqrt_a < kMinSqrtA) {
    reader.fail(record_line + 2,
                fmt::format("PRN {} (record at line {}), broadcast orbit line 2, field 4: sqrt A = {:g} "
                            "sqrt(m) puts the orbit inside the Earth (at least {} expected)",
                            prn, record_line, e.sqrt_a, kMinSqrtA));
  }
}

/// The week of toe as RINEX gives it is continuous; a file that wrote it modulo 1024 is
/// repaired from the epoch (toc) line, which carries the full date.
int reconcile_week(int week, double toe_s, const GpsTime& toc) {
  const double dt = toc.seconds_since(GpsTime{week, toe_s});
  const double rollovers = std::round(dt / (1024.0 * kSecondsPerWeek));
  return week + 1024 * static_cast<int>(rollovers);
}

Ephemeris read_gps_record(LineReader& reader, std::string_view first_line, double version) {
  const int record_line = reader.line_no();
  const EpochLine ep = parse_epoch_line(reader, first_line, version, gps::kMaxPrn);
  std::array<std::array<double, 4>, kOrbitLines> o{};
  for (int i = 0; i < kOrbitLines; ++i) {
    o[static_cast<std::size_t>(i)] =
        read_orbit_line(reader, version, i + 1, i + 1 < kOrbitLines ? 4 : 1, ep.prn, record_line);
  }
  Ephemeris eph;
  eph.prn = ep.prn;
  eph.af0_s = ep.clock[0];
  eph.af1_sps = ep.clock[1];
  eph.af2_sps2 = ep.clock[2];
  const GpsTime toc = gps_time_from_calendar(ep.toc);
  eph.toc_s = toc.sow;

  with_context(reader, fmt::format("record of PRN {} starting at line {}", ep.prn, record_line), [&] {
    eph.iode = to_int(o[0][0], "IODE", 0, 255);
    eph.crs_m = o[0][1];
    eph.delta_n_radps = o[0][2];
    eph.m0_rad = o[0][3];
    eph.cuc_rad = o[1][0];
    eph.e = o[1][1];
    eph.cus_rad = o[1][2];
    eph.sqrt_a = o[1][3];
    eph.toe_s = o[2][0];
    eph.cic_rad = o[2][1];
    eph.omega0_rad = o[2][2];
    eph.cis_rad = o[2][3];
    eph.i0_rad = o[3][0];
    eph.crc_m = o[3][1];
    eph.omega_rad = o[3][2];
    eph.omega_dot_radps = o[3][3];
    eph.idot_radps = o[4][0];
    eph.code_on_l2 = to_int(o[4][1], "codes on L2", 0, 3);
    eph.week = to_int(o[4][2], "GPS week", 0, 100000);
    eph.l2p_data_flag = to_int(o[4][3], "L2 P data flag", 0, 1);
    eph.ura_index = ura_index_from_metres(o[5][0]);
    eph.health = to_int(o[5][1], "SV health", 0, 63);
    eph.tgd_s = o[5][2];
    eph.iodc = to_int(o[5][3], "IODC", 0, 1023);
    eph.transmission_time_known = std::abs(o[6][0]) < kUnknownTransmit;
    eph.transmission_time_s = eph.transmission_time_known ? o[6][0] : 0.0;
    eph.fit_interval_flag = o[6][1] > 4.0 ? 1 : 0;  // RINEX gives hours; 0 means not known
    if (!(eph.e >= 0.0 && eph.e < 1.0))
      throw std::invalid_argument(fmt::format("eccentricity {} not in [0, 1)", eph.e));
    if (!(eph.sqrt_a > 0.0)) throw std::invalid_argument(fmt::format("sqrt(A) {} is not positive", eph.sqrt_a));
    if (!(eph.toe_s >= 0.0 && eph.toe_s < kSecondsPerWeek)) {
      throw std::invalid_argument(fmt::format("toe {} not in [0, 604800)", eph.toe_s));
    }
    return 0;
  });
  check_broadcast_ranges(reader, record_line, ep.prn, eph);
  eph.week = reconcile_week(eph.week, eph.toe_s, toc);
  return eph;
}

/// A Galileo record's values against the I/NAV fields that carry them (the word encoder
/// checks each field's width); angles may come in any normalisation, so they are wrapped into
/// one turn first. The error names the record and the field.
void check_galileo_ranges(const LineReader& reader, int record_line, const galileo::GalileoEphemeris& eph) {
  galileo::GalileoEphemeris wrapped = eph;
  for (double* angle :
       {&wrapped.orbit.m0_rad, &wrapped.orbit.omega0_rad, &wrapped.orbit.omega_rad, &wrapped.orbit.i0_rad}) {
    *angle = std::remainder(*angle, 2.0 * galileo::kPi);
  }
  wrapped.iod_nav = 0;  // checked as a whole number on its own
  with_context(reader, fmt::format("record of E{:02d} starting at line {}", eph.prn, record_line), [&] {
    for (int type = 1; type <= 4; ++type) galileo::inav::encode_ephemeris_word(type, wrapped);
    return 0;
  });
  constexpr double kMinSqrtA = 2525.0;  // sqrt of the Earth's equatorial radius, 6378137 m
  if (eph.orbit.sqrt_a < kMinSqrtA) {
    reader.fail(record_line + 2,
                fmt::format("E{:02d} (record at line {}), broadcast orbit line 2, field 4: sqrt A = {:g} "
                            "sqrt(m) puts the orbit inside the Earth (at least {} expected)",
                            eph.prn, record_line, eph.orbit.sqrt_a, kMinSqrtA));
  }
}

/// Health bits of a RINEX Galileo record: E1-B DVS (bit 0) and HS (1-2), E5a DVS (3) and HS
/// (4-5), E5b DVS (6) and HS (7-8).
galileo::SignalStatus signal_status(int bits, int first_bit) {
  return {(bits >> (first_bit + 1)) & 3, ((bits >> first_bit) & 1) != 0};
}

/// A Galileo record of RINEX 3 (Table A8 of RINEX 3.04): the epoch line with toc and the clock,
/// then seven broadcast orbit lines.
galileo::GalileoEphemeris read_galileo_record(LineReader& reader, std::string_view first_line, double version) {
  const int record_line = reader.line_no();
  const EpochLine ep = parse_epoch_line(reader, first_line, version, galileo::kMaxPrn);
  std::array<std::array<double, 4>, kOrbitLines> o{};
  for (int i = 0; i < kOrbitLines; ++i) {
    o[static_cast<std::size_t>(i)] =
        read_orbit_line(reader, version, i + 1, i + 1 < kOrbitLines ? (i == 4 ? 3 : 4) : 1, ep.prn, record_line);
  }
  galileo::GalileoEphemeris eph;
  eph.prn = ep.prn;
  eph.af0_s = ep.clock[0];
  eph.af1_sps = ep.clock[1];
  eph.af2_sps2 = ep.clock[2];
  // The epoch is on GST, whose labels are GPS time's up to the GGTO: week and seconds alike.
  const GpsTime toc = gps_time_from_calendar(ep.toc);
  eph.toc_s = toc.sow;
  KeplerElements& k = eph.orbit;
  int rinex_week = 0;
  with_context(reader, fmt::format("record of E{:02d} starting at line {}", ep.prn, record_line), [&] {
    eph.iod_nav = to_int(o[0][0], "IODnav", 0, 1023);
    k.crs_m = o[0][1];
    k.delta_n_radps = o[0][2];
    k.m0_rad = o[0][3];
    k.cuc_rad = o[1][0];
    k.e = o[1][1];
    k.cus_rad = o[1][2];
    k.sqrt_a = o[1][3];
    k.toe_s = o[2][0];
    k.cic_rad = o[2][1];
    k.omega0_rad = o[2][2];
    k.cis_rad = o[2][3];
    k.i0_rad = o[3][0];
    k.crc_m = o[3][1];
    k.omega_rad = o[3][2];
    k.omega_dot_radps = o[3][3];
    k.idot_radps = o[4][0];
    eph.data_sources = to_int(o[4][1], "data sources", 0, 1023);
    rinex_week = to_int(o[4][2], "GAL week", galileo::kGstWeekOffsetFromGps, 100000);
    eph.sisa_index = galileo::sisa_index_from_metres(o[5][0]);
    const int health = to_int(o[5][1], "SV health", 0, 511);
    eph.e1b = signal_status(health, 0);
    eph.e5a = signal_status(health, 3);
    eph.e5b = signal_status(health, 6);
    eph.bgd_e1e5a_s = o[5][2];
    eph.bgd_e1e5b_s = o[5][3];
    eph.transmission_time_known = std::abs(o[6][0]) < kUnknownTransmit;
    eph.transmission_time_s = eph.transmission_time_known ? o[6][0] : 0.0;
    if (!(k.e >= 0.0 && k.e < 1.0)) throw std::invalid_argument(fmt::format("eccentricity {} not in [0, 1)", k.e));
    if (!(k.toe_s >= 0.0 && k.toe_s < kSecondsPerWeek)) {
      throw std::invalid_argument(fmt::format("toe {} not in [0, 604800)", k.toe_s));
    }
    return 0;
  });
  check_galileo_ranges(reader, record_line, eph);
  eph.week = reconcile_week(rinex_week, k.toe_s, toc) - galileo::kGstWeekOffsetFromGps;
  return eph;
}

/// Lines of a RINEX 3 record of another satellite system: its continuation lines start with
/// blanks (GLONASS/SBAS have 3 or 4 of them, Galileo/BeiDou/QZSS/IRNSS 7, depending on version).
void skip_other_record(LineReader& reader, std::istream& in) {
  std::string line;
  while (in.peek() == ' ') {
    if (!reader.next(line)) return;
  }
}

}  // namespace

int ura_index_from_metres(double ura_m) {
  // Upper bounds of each URA index's range (IS-GPS-200 20.3.3.3.1.3).
  static constexpr std::array<double, 15> kBounds = {2.4,  3.4,   4.85,  6.85,  9.65,   13.65,  24.0,  48.0,
                                                     96.0, 192.0, 384.0, 768.0, 1536.0, 3072.0, 6144.0};
  for (std::size_t i = 0; i < kBounds.size(); ++i) {
    if (ura_m <= kBounds[i]) return static_cast<int>(i);
  }
  return 15;
}

double ura_metres_from_index(int ura_index) {
  // Nominal values of IS-GPS-200: 2^(1 + N/2) up to N = 6, 2^(N - 2) above; N = 15 means
  // no accuracy prediction, written as a value that reads back as 15.
  static constexpr std::array<double, 16> kNominal = {2.0,  2.8,   4.0,   5.7,   8.0,    11.3,   16.0,   32.0,
                                                      64.0, 128.0, 256.0, 512.0, 1024.0, 2048.0, 4096.0, 8192.0};
  return kNominal[static_cast<std::size_t>(std::clamp(ura_index, 0, 15))];
}

NavData read_rinex_nav(std::istream& in, const std::string& name) {
  LineReader reader(in, name);
  NavData nav;
  nav.source = name;
  const Header header = read_header(reader, nav);
  std::string line;
  while (reader.next_nonblank(line)) {
    if (header.version < 3.0) {
      if (trim(column(line, 0, 2)).empty()) reader.fail("expected a record starting with a PRN in columns 1-2");
      nav.ephemerides.push_back(read_gps_record(reader, line, header.version));
      continue;
    }
    const char system = line[0];
    if (system == 'G') {
      nav.ephemerides.push_back(read_gps_record(reader, line, header.version));
    } else if (system == 'E') {
      nav.galileo_ephemerides.push_back(read_galileo_record(reader, line, header.version));
    } else if (system >= 'A' && system <= 'Z') {
      skip_other_record(reader, in);
      ++nav.skipped_records;
    } else {
      reader.fail(fmt::format("expected a record starting with a satellite system letter in column 1, got '{}'", line));
    }
  }
  if (in.bad()) reader.fail("read error");
  return nav;
}

NavData read_rinex_nav(const std::string& path) {
  // A path that cannot be looked up (too long) is a file that cannot be opened, below.
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) check_input_file(path, "RINEX navigation file", kMaxTextInputBytes);
  std::ifstream file(path);
  if (!file) throw std::runtime_error(fmt::format("{}: cannot open RINEX navigation file", path));
  return read_rinex_nav(file, path);
}

const galileo::GalileoEphemeris* select_galileo_ephemeris(const NavData& nav, int svid, const galileo::GstTime& t) {
  constexpr double kValidity_s = 4.0 * 3600.0;
  const galileo::GalileoEphemeris* best = nullptr;
  double best_dt = 0.0;
  bool best_future = false;
  for (const galileo::GalileoEphemeris& eph : nav.galileo_ephemerides) {
    if (eph.prn != svid || (eph.data_sources & 1) == 0 || !eph.healthy_on_e1b()) continue;
    const double dt = t.seconds_since(galileo::GstTime{eph.week, eph.orbit.toe_s});
    if (std::abs(dt) > kValidity_s) continue;
    // The transmission time is a second of toe's week (RINEX may refer it to toe's week).
    const bool future =
        eph.transmission_time_known && seconds_of_week_difference(eph.transmission_time_s, eph.orbit.toe_s) > dt;
    if (best == nullptr || (best_future && !future) || (future == best_future && std::abs(dt) < best_dt)) {
      best = &eph;
      best_dt = std::abs(dt);
      best_future = future;
    }
  }
  return best;
}

const Ephemeris* NavData::select(int prn, const GpsTime& t) const {
  const Ephemeris* best = nullptr;
  bool best_future = true;
  double best_dt = 0.0;
  for (const Ephemeris& eph : ephemerides) {
    if (eph.prn != prn || !eph.healthy()) continue;
    const GpsTime toe{eph.week, eph.toe_s};
    const double dt = std::abs(t.seconds_since(toe));
    if (dt > fit_interval_s(eph) / 2) continue;
    // Transmission time relative to toe: RINEX 3 may shift it by a week to refer to toe's week.
    const double tx_since_toe = seconds_of_week_difference(eph.transmission_time_s, eph.toe_s);
    const bool future = eph.transmission_time_known && toe.plus_seconds(tx_since_toe).seconds_since(t) > 0.0;
    if (best == nullptr || (best_future && !future) || (future == best_future && dt < best_dt)) {
      best = &eph;
      best_future = future;
      best_dt = dt;
    }
  }
  return best;
}

// ---------------------------------------------------------------------------
// Writer

namespace {

/// Fortran D19.12 as RINEX 3 writes it (E exponent, mantissa in [1, 10)).
std::string d19(double value, const char* what, int prn) {
  if (!std::isfinite(value) || std::abs(value) >= 1e99) {
    throw std::invalid_argument(fmt::format("write_rinex3_nav: {} of PRN {} is not writable: {}", what, prn, value));
  }
  if (std::abs(value) < 1e-99) value = 0.0;  // keeps the exponent at two digits
  return fmt::format("{:19.12E}", value);
}

std::string header_line(const std::string& content, const char* label) {
  return fmt::format("{:<60.60}{:<20}\n", content, label);
}

/// toc with its week (toe's week, unless toc lies across a week boundary from toe), rounded
/// to the whole second the epoch line can hold.
GpsTime full_toc(const Ephemeris& eph) {
  return GpsTime::normalized(eph.week, std::round(eph.toe_s + seconds_of_week_difference(eph.toc_s, eph.toe_s)));
}

/// A record's first line (RINEX 3.04 Table A4/A8): satellite, toc as a calendar epoch, clock.
void write_clock_line(std::ostream& out, char system, int prn, const GpsTime& toc, double af0_s, double af1_sps,
                      double af2_sps2) {
  const CalendarTime c = calendar_from_gps_time(toc);
  const int seconds = static_cast<int>(std::lround(c.second));
  out << fmt::format("{}{:02d} {:04d} {:02d} {:02d} {:02d} {:02d} {:02d}", system, prn, c.year, c.month, c.day, c.hour,
                     c.minute, seconds)
      << d19(af0_s, "af0", prn) << d19(af1_sps, "af1", prn) << d19(af2_sps2, "af2", prn) << '\n';
}

/// One of a record's broadcast orbit lines: four (or fewer) fields after four blanks.
void write_orbit_line(std::ostream& out, int prn, std::initializer_list<double> values) {
  out << "    ";
  for (double v : values) out << d19(v, "orbit field", prn);
  out << '\n';
}

void write_record(std::ostream& out, const Ephemeris& e) {
  write_clock_line(out, 'G', e.prn, full_toc(e), e.af0_s, e.af1_sps, e.af2_sps2);
  const auto orbit = [&](std::initializer_list<double> values) { write_orbit_line(out, e.prn, values); };
  orbit({static_cast<double>(e.iode), e.crs_m, e.delta_n_radps, e.m0_rad});
  orbit({e.cuc_rad, e.e, e.cus_rad, e.sqrt_a});
  orbit({e.toe_s, e.cic_rad, e.omega0_rad, e.cis_rad});
  orbit({e.i0_rad, e.crc_m, e.omega_rad, e.omega_dot_radps});
  orbit({e.idot_radps, static_cast<double>(e.code_on_l2), static_cast<double>(e.week),
         static_cast<double>(e.l2p_data_flag)});
  orbit({ura_metres_from_index(e.ura_index), static_cast<double>(e.health), e.tgd_s, static_cast<double>(e.iodc)});
  orbit({e.transmission_time_known ? e.transmission_time_s : 0.9999e9, fit_interval_s(e) / 3600.0});
}

/// toc of a Galileo record on GST with its full week (toe's week unless toc lies across a
/// week boundary from toe), rounded to a whole second, labelled as a GPS time: the two
/// scales share second and week boundaries (week offset 1024).
GpsTime galileo_full_toc(const galileo::GalileoEphemeris& eph) {
  const double toe = eph.orbit.toe_s;
  return GpsTime::normalized(eph.week + galileo::kGstWeekOffsetFromGps,
                             std::round(toe + seconds_of_week_difference(eph.toc_s, toe)));
}

/// The RINEX health bits of a signal status (the inverse of signal_status).
int status_bits(const galileo::SignalStatus& s, int first_bit) {
  return ((s.health & 3) << (first_bit + 1)) | ((s.data_invalid ? 1 : 0) << first_bit);
}

void write_galileo_record(std::ostream& out, const galileo::GalileoEphemeris& e) {
  write_clock_line(out, 'E', e.prn, galileo_full_toc(e), e.af0_s, e.af1_sps, e.af2_sps2);
  const auto orbit = [&](std::initializer_list<double> values) { write_orbit_line(out, e.prn, values); };
  const KeplerElements& k = e.orbit;
  const int health = status_bits(e.e1b, 0) | status_bits(e.e5a, 3) | status_bits(e.e5b, 6);
  // RINEX writes -1 m where no accuracy prediction is available (NAPA).
  const double sisa_m = galileo::sisa_metres(e.sisa_index).value_or(-1.0);
  orbit({static_cast<double>(e.iod_nav), k.crs_m, k.delta_n_radps, k.m0_rad});
  orbit({k.cuc_rad, k.e, k.cus_rad, k.sqrt_a});
  orbit({k.toe_s, k.cic_rad, k.omega0_rad, k.cis_rad});
  orbit({k.i0_rad, k.crc_m, k.omega_rad, k.omega_dot_radps});
  orbit({k.idot_radps, static_cast<double>(e.data_sources),
         static_cast<double>(e.week + galileo::kGstWeekOffsetFromGps)});
  orbit({sisa_m, static_cast<double>(health), e.bgd_e1e5a_s, e.bgd_e1e5b_s});
  orbit({e.transmission_time_known ? e.transmission_time_s : 0.9999e9});
}

/// The header's date: the latest toc of the records (GPS ones when there are any, which
/// keeps a GPS-only file's bytes as they were), not the wall clock.
std::string header_date(const NavData& nav) {
  std::optional<GpsTime> latest;
  const auto consider = [&latest](const GpsTime& t) {
    if (!latest || t.seconds_since(*latest) > 0) latest = t;
  };
  for (const Ephemeris& e : nav.ephemerides) consider(full_toc(e));
  for (const galileo::GalileoEphemeris& e : nav.galileo_ephemerides) consider(galileo_full_toc(e));
  if (!latest) return "                   ";
  const CalendarTime c = calendar_from_gps_time(*latest);
  return fmt::format("{:04d}{:02d}{:02d} {:02d}{:02d}{:02d} GPS", c.year, c.month, c.day, c.hour, c.minute,
                     static_cast<int>(c.second));
}

/// "G: GPS", "E: GALILEO" or "M: MIXED" by the records present (GPS when there are none).
std::string file_system(const NavData& nav) {
  const bool gps = !nav.ephemerides.empty() || nav.galileo_ephemerides.empty();
  const bool gal = !nav.galileo_ephemerides.empty();
  if (gps && gal) return "M: MIXED";
  return gal ? "E: GALILEO" : "G: GPS";
}

/// A TIME SYSTEM CORR line (GPUT, GAGP, GAUT): a0, a1, reference time and week.
std::string time_system_corr(const char* kind, double a0, double a1, int t_ref_s, int week) {
  return header_line(fmt::format("{} {:17.10E}{:16.9E} {:6d} {:4d}", kind, a0, a1, t_ref_s, week), "TIME SYSTEM CORR");
}

}  // namespace

void write_rinex3_nav(std::ostream& out, const NavData& nav, const std::string& program_name) {
  out << header_line(fmt::format("{:>9.2f}{:11}{:<20}{:<20}", 3.04, "", "N: GNSS NAV DATA", file_system(nav)),
                     "RINEX VERSION / TYPE");
  out << header_line(fmt::format("{:<20.20}{:<20}{:<20}", program_name, "", header_date(nav)), "PGM / RUN BY / DATE");
  if (nav.iono.valid) {
    const auto& a = nav.iono.alpha;
    const auto& b = nav.iono.beta;
    out << header_line(fmt::format("GPSA {:12.4E}{:12.4E}{:12.4E}{:12.4E}", a[0], a[1], a[2], a[3]),
                       "IONOSPHERIC CORR");
    out << header_line(fmt::format("GPSB {:12.4E}{:12.4E}{:12.4E}{:12.4E}", b[0], b[1], b[2], b[3]),
                       "IONOSPHERIC CORR");
  }
  if (nav.galileo_iono.valid) {
    const auto& g = nav.galileo_iono;
    out << header_line(
        fmt::format("GAL  {:12.4E}{:12.4E}{:12.4E}{:12.4E}", g.ai0_sfu, g.ai1_sfu_per_deg, g.ai2_sfu_per_deg2, 0.0),
        "IONOSPHERIC CORR");
  }
  if (nav.utc.valid) out << time_system_corr("GPUT", nav.utc.a0_s, nav.utc.a1_sps, nav.utc.tot_s, nav.utc.wnt);
  // RINEX counts the Galileo weeks of these lines continuously with GPS weeks.
  if (nav.ggto.valid) {
    out << time_system_corr("GAGP", nav.ggto.a0g_s, nav.ggto.a1g_sps, nav.ggto.t0g_s,
                            nav.ggto.wn0g + galileo::kGstWeekOffsetFromGps);
  }
  if (nav.galileo_utc.valid) {
    const UtcParameters& u = nav.galileo_utc;
    out << time_system_corr("GAUT", u.a0_s, u.a1_sps, u.tot_s, u.wnt + galileo::kGstWeekOffsetFromGps);
  }
  if (nav.leap_seconds_valid) {
    const UtcParameters& u = nav.utc;
    const bool future_known = u.wn_lsf != 0 || u.delta_t_lsf != 0;
    out << header_line(future_known ? fmt::format("{:6d}{:6d}{:6d}{:6d}", u.delta_t_ls, u.delta_t_lsf, u.wn_lsf, u.dn)
                                    : fmt::format("{:6d}", u.delta_t_ls),
                       "LEAP SECONDS");
  }
  out << header_line("", "END OF HEADER");
  for (const Ephemeris& e : nav.ephemerides) write_record(out, e);
  for (const galileo::GalileoEphemeris& e : nav.galileo_ephemerides) write_galileo_record(out, e);
}

}  // namespace deepnav
