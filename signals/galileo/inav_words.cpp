#include "signals/galileo/inav_words.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "signals/galileo/galileo_constants.hpp"

namespace deepnav::galileo::inav {
namespace {

constexpr int kTypeBits = 6;
constexpr double kSemicircle = kPi;  // the ICD's semicircles, in radians

/// Writes fields one after the other into a word, from bit 6 on.
class WordWriter {
 public:
  explicit WordWriter(int type) { put_raw(static_cast<std::uint64_t>(type), kTypeBits, "word type"); }

  /// `value` / `lsb` rounded into `bits` bits, two's complement when `is_signed`.
  void field(double value, int bits, double lsb, bool is_signed, const char* name) {
    const double scaled = std::round(value / lsb);
    const double lo = is_signed ? -std::ldexp(1.0, bits - 1) : 0.0;
    const double hi = is_signed ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
    if (!(scaled >= lo && scaled <= hi)) {
      throw std::invalid_argument(fmt::format("I/NAV word {}: {} = {:g} does not fit its {}-bit field (LSB {:g}, {})",
                                              type_, name, value, bits, lsb, is_signed ? "signed" : "unsigned"));
    }
    const auto raw = static_cast<std::int64_t>(scaled);
    put_raw(static_cast<std::uint64_t>(raw) & ((std::uint64_t{1} << bits) - 1), bits, name);
  }
  void field(int value, int bits, bool is_signed, const char* name) {
    field(double(value), bits, 1.0, is_signed, name);
  }
  void field(bool value, const char* name) { field(value ? 1 : 0, 1, false, name); }
  void skip(int bits) { put_raw(0, bits, "spare"); }

  Word word() const {
    if (pos_ != kWordBits) throw std::logic_error(fmt::format("I/NAV word {}: layout of {} bits", type_, pos_));
    return word_;
  }

 private:
  void put_raw(std::uint64_t raw, int bits, const char* name) {
    if (pos_ + bits > kWordBits)
      throw std::logic_error(fmt::format("I/NAV word {}: {} overruns the word", type_, name));
    // A spare run may be wider than the 64-bit value: its upper bits are zero (and a shift
    // by 64 or more is undefined).
    for (int k = bits - 1; k >= 0; --k) word_[static_cast<std::size_t>(pos_++)] = k < 64 && ((raw >> k) & 1);
    if (pos_ == kTypeBits) type_ = static_cast<int>(raw);
  }

  Word word_{};
  int pos_ = 0;
  int type_ = 0;
};

/// Reads fields in the writer's order.
class WordReader {
 public:
  explicit WordReader(const Word& word) : word_(word) {}

  void field(double& value, int bits, double lsb, bool is_signed, const char*) {
    std::int64_t raw = static_cast<std::int64_t>(get_raw(bits));
    if (is_signed && (raw >> (bits - 1)) & 1) raw -= std::int64_t{1} << bits;
    value = static_cast<double>(raw) * lsb;
  }
  void field(int& value, int bits, bool is_signed, const char* name) {
    double v = 0.0;
    field(v, bits, 1.0, is_signed, name);
    value = static_cast<int>(v);
  }
  void field(bool& value, const char*) { value = get_raw(1) != 0; }
  void skip(int bits) { get_raw(bits); }

 private:
  std::uint64_t get_raw(int bits) {
    std::uint64_t raw = 0;
    for (int k = 0; k < bits; ++k) raw = (raw << 1) | word_[static_cast<std::size_t>(pos_++)];
    return raw;
  }

  const Word& word_;
  int pos_ = kTypeBits;
};

// One layout per word type, shared by encoding and decoding (Io is WordWriter or WordReader;
// T is the content, const-stripped for the writer's copy). ICD Tables 60 to 70.

template <typename Io>
void ephemeris_layout(int type, Io& io, GalileoEphemeris& e, int& iod) {
  KeplerElements& o = e.orbit;
  io.field(iod, 10, false, "IODnav");
  switch (type) {
    case 1:
      io.field(o.toe_s, 14, 60.0, false, "t0e");
      io.field(o.m0_rad, 32, 0x1p-31 * kSemicircle, true, "M0");
      io.field(o.e, 32, 0x1p-33, false, "e");
      io.field(o.sqrt_a, 32, 0x1p-19, false, "sqrt A");
      io.skip(2);
      return;
    case 2:
      io.field(o.omega0_rad, 32, 0x1p-31 * kSemicircle, true, "OMEGA0");
      io.field(o.i0_rad, 32, 0x1p-31 * kSemicircle, true, "i0");
      io.field(o.omega_rad, 32, 0x1p-31 * kSemicircle, true, "omega");
      io.field(o.idot_radps, 14, 0x1p-43 * kSemicircle, true, "IDOT");
      io.skip(2);
      return;
    case 3:
      io.field(o.omega_dot_radps, 24, 0x1p-43 * kSemicircle, true, "OMEGA dot");
      io.field(o.delta_n_radps, 16, 0x1p-43 * kSemicircle, true, "delta n");
      io.field(o.cuc_rad, 16, 0x1p-29, true, "Cuc");
      io.field(o.cus_rad, 16, 0x1p-29, true, "Cus");
      io.field(o.crc_m, 16, 0x1p-5, true, "Crc");
      io.field(o.crs_m, 16, 0x1p-5, true, "Crs");
      io.field(e.sisa_index, 8, false, "SISA(E1,E5b)");
      return;
    case 4:
      io.field(e.prn, 6, false, "SVID");
      io.field(o.cic_rad, 16, 0x1p-29, true, "Cic");
      io.field(o.cis_rad, 16, 0x1p-29, true, "Cis");
      io.field(e.toc_s, 14, 60.0, false, "t0c");
      io.field(e.af0_s, 31, 0x1p-34, true, "af0");
      io.field(e.af1_sps, 21, 0x1p-46, true, "af1");
      io.field(e.af2_sps2, 6, 0x1p-59, true, "af2");
      io.skip(2);
      return;
    default:
      throw std::invalid_argument(fmt::format("I/NAV: word type {} is not an ephemeris word (1..4)", type));
  }
}

template <typename Io>
void spare_layout(Io& io, SpareWord& w) {
  io.field(w.time_flag, 2, false, "time");
  io.skip(88);
  io.field(w.week, 12, false, "WN");
  io.field(w.tow_s, 20, false, "TOW");
}

template <typename Io>
void iono_delay_health_layout(Io& io, IonoDelayHealthWord& w) {
  io.field(w.iono.ai0_sfu, 11, 0x1p-2, false, "a_i0");
  io.field(w.iono.ai1_sfu_per_deg, 11, 0x1p-8, true, "a_i1");
  io.field(w.iono.ai2_sfu_per_deg2, 14, 0x1p-15, true, "a_i2");
  for (bool& flag : w.iono.region_disturbed) io.field(flag, "region flag");
  io.field(w.bgd_e1e5a_s, 10, 0x1p-32, true, "BGD(E1,E5a)");
  io.field(w.bgd_e1e5b_s, 10, 0x1p-32, true, "BGD(E1,E5b)");
  io.field(w.e5b.health, 2, false, "E5b HS");
  io.field(w.e1b.health, 2, false, "E1-B HS");
  io.field(w.e5b.data_invalid, "E5b DVS");
  io.field(w.e1b.data_invalid, "E1-B DVS");
  io.field(w.week, 12, false, "WN");
  io.field(w.tow_s, 20, false, "TOW");
  io.skip(23);
}

template <typename Io>
void utc_layout(Io& io, UtcWord& w) {
  UtcParameters& u = w.utc;
  io.field(u.a0_s, 32, 0x1p-30, true, "A0");
  io.field(u.a1_sps, 24, 0x1p-50, true, "A1");
  io.field(u.delta_t_ls, 8, true, "delta t_LS");
  double tot = u.tot_s;
  io.field(tot, 8, 3600.0, false, "t0t");
  u.tot_s = static_cast<int>(tot);
  io.field(u.wnt, 8, false, "WN0t");
  io.field(u.wn_lsf, 8, false, "WN_LSF");
  io.field(u.dn, 3, false, "DN");
  io.field(u.delta_t_lsf, 8, true, "delta t_LSF");
  io.field(w.tow_s, 20, false, "TOW");
  io.skip(3);
}

/// The orbit fields of an almanac entry: words 9 and 10 split them after delta i.
template <typename Io>
void almanac_orbit(Io& io, AlmanacEntry& a, bool head, bool tail) {
  if (head) {
    io.field(a.svid, 6, false, "SVID");
    io.field(a.delta_sqrt_a, 13, 0x1p-9, true, "delta sqrt A");
    io.field(a.e, 11, 0x1p-16, false, "e");
    io.field(a.omega_rad, 16, 0x1p-15 * kSemicircle, true, "omega");
    io.field(a.delta_i_rad, 11, 0x1p-14 * kSemicircle, true, "delta i");
  }
  if (tail) {
    io.field(a.omega0_rad, 16, 0x1p-15 * kSemicircle, true, "OMEGA0");
    io.field(a.omega_dot_radps, 11, 0x1p-33 * kSemicircle, true, "OMEGA dot");
  }
}

template <typename Io>
void almanac_clock(Io& io, AlmanacEntry& a) {
  io.field(a.af0_s, 16, 0x1p-19, true, "af0");
  io.field(a.af1_sps, 13, 0x1p-38, true, "af1");
  io.field(a.e5b_health, 2, false, "E5b HS");
  io.field(a.e1b_health, 2, false, "E1-B HS");
}

template <typename Io>
void almanac_epoch(Io& io, AlmanacBatch& b) {
  io.field(b.week, 2, false, "WNa");
  double t0a = b.t0a_s;
  io.field(t0a, 10, 600.0, false, "t0a");
  b.t0a_s = static_cast<int>(t0a);
}

template <typename Io>
void almanac_layout(int type, Io& io, AlmanacBatch& b) {
  io.field(b.iod_a, 4, false, "IODa");
  switch (type) {
    case 7:
      almanac_epoch(io, b);
      almanac_orbit(io, b.sv[0], true, true);
      io.field(b.sv[0].m0_rad, 16, 0x1p-15 * kSemicircle, true, "M0");
      io.skip(6);
      return;
    case 8:
      almanac_clock(io, b.sv[0]);
      almanac_orbit(io, b.sv[1], true, true);
      io.skip(1);
      return;
    case 9:
      almanac_epoch(io, b);
      io.field(b.sv[1].m0_rad, 16, 0x1p-15 * kSemicircle, true, "M0");
      almanac_clock(io, b.sv[1]);
      almanac_orbit(io, b.sv[2], true, false);
      return;
    case 10: {
      almanac_orbit(io, b.sv[2], false, true);
      io.field(b.sv[2].m0_rad, 16, 0x1p-15 * kSemicircle, true, "M0");
      almanac_clock(io, b.sv[2]);
      GgtoParameters& g = b.ggto;
      io.field(g.a0g_s, 16, 0x1p-35, true, "A0G");
      io.field(g.a1g_sps, 12, 0x1p-51, true, "A1G");
      double t0g = g.t0g_s;
      io.field(t0g, 8, 3600.0, false, "t0G");
      g.t0g_s = static_cast<int>(t0g);
      io.field(g.wn0g, 6, false, "WN0G");
      return;
    }
    default:
      throw std::invalid_argument(fmt::format("I/NAV: word type {} is not an almanac word (7..10)", type));
  }
}

void expect_type(const Word& word, int type, const char* what) {
  if (word_type(word) != type) {
    throw std::invalid_argument(fmt::format("I/NAV: expected word type {} ({}), got {}", type, what, word_type(word)));
  }
}

}  // namespace

int word_type(const Word& word) {
  int type = 0;
  for (int k = 0; k < kTypeBits; ++k) type = (type << 1) | word[static_cast<std::size_t>(k)];
  return type;
}

Word encode_ephemeris_word(int type, const GalileoEphemeris& eph) {
  WordWriter io(type);
  GalileoEphemeris copy = eph;
  int iod = eph.iod_nav;
  ephemeris_layout(type, io, copy, iod);
  return io.word();
}

Word encode_spare_word(const SpareWord& w) {
  WordWriter io(0);
  SpareWord copy = w;
  spare_layout(io, copy);
  return io.word();
}

Word encode_iono_delay_health_word(const IonoDelayHealthWord& w) {
  WordWriter io(5);
  IonoDelayHealthWord copy = w;
  iono_delay_health_layout(io, copy);
  return io.word();
}

Word encode_utc_word(const UtcWord& w) {
  WordWriter io(6);
  UtcWord copy = w;
  utc_layout(io, copy);
  return io.word();
}

Word encode_almanac_word(int type, const AlmanacBatch& batch) {
  WordWriter io(type);
  AlmanacBatch copy = batch;
  almanac_layout(type, io, copy);
  return io.word();
}

Word encode_dummy_word() {
  WordWriter io(kDummyWordType);
  io.skip(kWordBits - kTypeBits);
  return io.word();
}

int decode_ephemeris_word(const Word& word, GalileoEphemeris& eph) {
  WordReader io(word);
  int iod = 0;
  ephemeris_layout(word_type(word), io, eph, iod);
  eph.iod_nav = iod;
  return iod;
}

SpareWord decode_spare_word(const Word& word) {
  expect_type(word, 0, "spare");
  WordReader io(word);
  SpareWord w;
  spare_layout(io, w);
  return w;
}

IonoDelayHealthWord decode_iono_delay_health_word(const Word& word) {
  expect_type(word, 5, "ionosphere, BGD, health, GST");
  WordReader io(word);
  IonoDelayHealthWord w;
  iono_delay_health_layout(io, w);
  w.iono.valid = true;
  return w;
}

UtcWord decode_utc_word(const Word& word) {
  expect_type(word, 6, "GST-UTC");
  WordReader io(word);
  UtcWord w;
  utc_layout(io, w);
  w.utc.valid = true;
  return w;
}

void decode_almanac_word(const Word& word, AlmanacBatch& batch) {
  WordReader io(word);
  almanac_layout(word_type(word), io, batch);
  if (word_type(word) == 10) batch.ggto.valid = true;
}

void EphemerisAssembler::add(const Word& word) {
  const int type = word_type(word);
  if (type >= 1 && type <= 4) {
    iod_of_word_[static_cast<std::size_t>(type - 1)] = decode_ephemeris_word(word, eph_);
  } else if (type == 5) {
    word5_ = decode_iono_delay_health_word(word);
  }
}

std::optional<GalileoEphemeris> EphemerisAssembler::ephemeris() const {
  if (!word5_) return std::nullopt;
  for (const auto& iod : iod_of_word_) {
    if (!iod || *iod != *iod_of_word_[0]) return std::nullopt;
  }
  GalileoEphemeris eph = eph_;
  eph.iod_nav = *iod_of_word_[0];
  eph.bgd_e1e5a_s = word5_->bgd_e1e5a_s;
  eph.bgd_e1e5b_s = word5_->bgd_e1e5b_s;
  eph.e1b = word5_->e1b;
  eph.e5b = word5_->e5b;
  // toe's week: the word's week, or the one before or after when toe is half a week away.
  const double dt = eph.orbit.toe_s - word5_->tow_s;
  eph.week = word5_->week + (dt > kSecondsPerWeek / 2 ? -1 : dt < -kSecondsPerWeek / 2 ? 1 : 0);
  return eph;
}

}  // namespace deepnav::galileo::inav
