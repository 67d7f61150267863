#include "signals/lnav_message.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ins/gps_time.hpp"
#include "signals/gps_constants.hpp"
#include "signals/lnav_parity.hpp"

namespace deepnav::lnav {
namespace {

using DataWords = SubframeData;

constexpr double kSemicircle = gps::kPi;  // message unit of angles -> radians
constexpr int kDataIdLnav = 1;            // binary 01: the NAV data structure of this appendix

// One field of a subframe. Split fields keep their first_bits high bits at `first` and the rest
// at `second` (e.g. M0: 8 MSBs in word 4, 24 LSBs in word 5).
struct Field {
  const char* name;
  int first;       ///< subframe bit (1..300) of the MSB
  int bits;        ///< total width
  double lsb;      ///< scale factor, message units
  bool is_signed;  ///< two's complement
  double unit;     ///< SI value of one message unit (pi for semicircles)
  int second = 0;
  int first_bits = 0;
};

constexpr Field plain(const char* name, int first, int bits, double lsb = 1.0, bool is_signed = false,
                      double unit = 1.0) {
  return {name, first, bits, lsb, is_signed, unit, 0, 0};
}
constexpr Field split(const char* name, int first, int first_bits, int second, int bits, double lsb, bool is_signed,
                      double unit = 1.0) {
  return {name, first, bits, lsb, is_signed, unit, second, first_bits};
}

// Subframe bit b (1..300) lives in word (b-1)/30 at word bit (b-1)%30+1; only d1..d24 hold data.
void put_bits(DataWords& d, int first, int n, std::uint64_t value) {
  for (int i = 0; i < n; ++i) {
    const int b = first + i - 1;
    const int word = b / kBitsPerWord, k = b % kBitsPerWord;
    if (k >= 24) throw std::logic_error(fmt::format("LNAV layout: subframe bit {} is a parity bit", b + 1));
    const auto bit = static_cast<std::uint32_t>((value >> (n - 1 - i)) & 1u);
    d[word] = (d[word] & ~(1u << (23 - k))) | (bit << (23 - k));
  }
}

std::uint64_t get_bits(const DataWords& d, int first, int n) {
  std::uint64_t value = 0;
  for (int i = 0; i < n; ++i) {
    const int b = first + i - 1;
    value = (value << 1) | ((d[b / kBitsPerWord] >> (23 - b % kBitsPerWord)) & 1u);
  }
  return value;
}

std::uint64_t low_mask(int bits) { return (std::uint64_t{1} << bits) - 1; }

void write_raw(DataWords& d, const Field& f, std::uint64_t raw) {
  if (f.second == 0) {
    put_bits(d, f.first, f.bits, raw);
    return;
  }
  const int low_bits = f.bits - f.first_bits;
  put_bits(d, f.first, f.first_bits, raw >> low_bits);
  put_bits(d, f.second, low_bits, raw & low_mask(low_bits));
}

std::uint64_t read_raw(const DataWords& d, const Field& f) {
  if (f.second == 0) return get_bits(d, f.first, f.bits);
  const int low_bits = f.bits - f.first_bits;
  return (get_bits(d, f.first, f.first_bits) << low_bits) | get_bits(d, f.second, low_bits);
}

// Quantizes an SI value to the field's LSB; a value outside the field's range is an error
// naming the field, never a silent wrap.
void encode_value(DataWords& d, const Field& f, double si_value, int subframe_id) {
  const double counts_real = si_value / f.unit / f.lsb;
  const std::int64_t lo = f.is_signed ? -(std::int64_t{1} << (f.bits - 1)) : 0;
  const std::int64_t hi = f.is_signed ? (std::int64_t{1} << (f.bits - 1)) - 1 : (std::int64_t{1} << f.bits) - 1;
  if (!std::isfinite(counts_real) || std::round(counts_real) < static_cast<double>(lo) ||
      std::round(counts_real) > static_cast<double>(hi)) {
    throw std::invalid_argument(fmt::format(
        "LNAV subframe {} field {}: value {} is outside the {}-bit {} range [{}, {}] x LSB {} x unit {}", subframe_id,
        f.name, si_value, f.bits, f.is_signed ? "two's complement" : "unsigned", lo, hi, f.lsb, f.unit));
  }
  const auto counts = static_cast<std::int64_t>(std::llround(counts_real));
  write_raw(d, f, static_cast<std::uint64_t>(counts) & low_mask(f.bits));
}

double decode_value(const DataWords& d, const Field& f) {
  const std::uint64_t raw = read_raw(d, f);
  auto counts = static_cast<std::int64_t>(raw);
  if (f.is_signed && (raw >> (f.bits - 1)) & 1u) counts -= std::int64_t{1} << f.bits;
  return static_cast<double>(counts) * f.lsb * f.unit;
}

int decode_int(const DataWords& d, const Field& f) { return static_cast<int>(std::lround(decode_value(d, f))); }

// ---- TLM and HOW (IS-GPS-200 Figure 20-2) ----
constexpr Field kPreambleField = plain("preamble", 1, 8);
constexpr Field kTlmMessage = plain("TLM message", 9, 14);
constexpr Field kIntegrity = plain("integrity flag", 23, 1);
constexpr Field kTlmReserved = plain("TLM reserved", 24, 1);
constexpr Field kTow = plain("TOW count", 31, 17);
constexpr Field kAlert = plain("alert flag", 48, 1);
constexpr Field kAntiSpoof = plain("anti-spoof flag", 49, 1);
constexpr Field kSubframeId = plain("subframe ID", 50, 3);

// ---- Subframe 1 (Table 20-I) ----
constexpr Field kWn = plain("WN", 61, 10);
constexpr Field kCodeOnL2 = plain("code on L2", 71, 2);
constexpr Field kUra = plain("URA index", 73, 4);
constexpr Field kHealth = plain("SV health", 77, 6);
constexpr Field kIodc = split("IODC", 83, 2, 211, 10, 1.0, false);
constexpr Field kL2p = plain("L2 P data flag", 91, 1);
constexpr Field kTgd = plain("TGD", 197, 8, 0x1p-31, true);
constexpr Field kToc = plain("toc", 219, 16, 16.0);
constexpr Field kAf2 = plain("af2", 241, 8, 0x1p-55, true);
constexpr Field kAf1 = plain("af1", 249, 16, 0x1p-43, true);
constexpr Field kAf0 = plain("af0", 271, 22, 0x1p-31, true);
// Reserved stretches of subframe 1: bits 92-114, words 5 and 6, bits 181-196.
constexpr std::array<std::array<int, 2>, 4> kSf1Reserved = {{{92, 23}, {121, 24}, {151, 24}, {181, 16}}};

// ---- Subframe 2 (Table 20-III) ----
constexpr Field kIode2 = plain("IODE", 61, 8);
constexpr Field kCrs = plain("Crs", 69, 16, 0x1p-5, true);
constexpr Field kDeltaN = plain("delta n", 91, 16, 0x1p-43, true, kSemicircle);
constexpr Field kM0 = split("M0", 107, 8, 121, 32, 0x1p-31, true, kSemicircle);
constexpr Field kCuc = plain("Cuc", 151, 16, 0x1p-29, true);
constexpr Field kE = split("e", 167, 8, 181, 32, 0x1p-33, false);
constexpr Field kCus = plain("Cus", 211, 16, 0x1p-29, true);
constexpr Field kSqrtA = split("sqrt A", 227, 8, 241, 32, 0x1p-19, false);
constexpr Field kToe = plain("toe", 271, 16, 16.0);
constexpr Field kFit = plain("fit interval flag", 287, 1);
constexpr Field kAodo = plain("AODO", 288, 5, 900.0);

// ---- Subframe 3 (Table 20-III) ----
constexpr Field kCic = plain("Cic", 61, 16, 0x1p-29, true);
constexpr Field kOmega0 = split("OMEGA0", 77, 8, 91, 32, 0x1p-31, true, kSemicircle);
constexpr Field kCis = plain("Cis", 121, 16, 0x1p-29, true);
constexpr Field kI0 = split("i0", 137, 8, 151, 32, 0x1p-31, true, kSemicircle);
constexpr Field kCrc = plain("Crc", 181, 16, 0x1p-5, true);
constexpr Field kOmega = split("omega", 197, 8, 211, 32, 0x1p-31, true, kSemicircle);
constexpr Field kOmegaDot = plain("OMEGADOT", 241, 24, 0x1p-43, true, kSemicircle);
constexpr Field kIode3 = plain("IODE", 271, 8);
constexpr Field kIdot = plain("IDOT", 279, 14, 0x1p-43, true, kSemicircle);

// ---- Subframes 4 and 5 ----
constexpr Field kDataId = plain("data ID", 61, 2);
constexpr Field kSvId = plain("SV ID", 63, 6);
constexpr int kFirstPageDataBit = 69;

// Almanac page (Table 20-VI, Figure 20-1 sheet 4).
constexpr Field kAlmE = plain("almanac e", 69, 16, 0x1p-21);
constexpr Field kAlmToa = plain("almanac toa", 91, 8, 4096.0);
constexpr Field kAlmDeltaI = plain("almanac delta i", 99, 16, 0x1p-19, true, kSemicircle);
constexpr Field kAlmOmegaDot = plain("almanac OMEGADOT", 121, 16, 0x1p-38, true, kSemicircle);
constexpr Field kAlmHealth = plain("almanac SV health", 137, 8);
constexpr Field kAlmSqrtA = plain("almanac sqrt A", 151, 24, 0x1p-11);
constexpr Field kAlmOmega0 = plain("almanac OMEGA0", 181, 24, 0x1p-23, true, kSemicircle);
constexpr Field kAlmOmega = plain("almanac omega", 211, 24, 0x1p-23, true, kSemicircle);
constexpr Field kAlmM0 = plain("almanac M0", 241, 24, 0x1p-23, true, kSemicircle);
constexpr Field kAlmAf0 = split("almanac af0", 271, 8, 290, 11, 0x1p-20, true);
constexpr Field kAlmAf1 = plain("almanac af1", 279, 11, 0x1p-38, true);

// Subframe 4 page 18: ionosphere (Table 20-X) and UTC (Table 20-IX).
constexpr std::array<Field, 4> kAlpha = {plain("alpha0", 69, 8, 0x1p-30, true), plain("alpha1", 77, 8, 0x1p-27, true),
                                         plain("alpha2", 91, 8, 0x1p-24, true), plain("alpha3", 99, 8, 0x1p-24, true)};
constexpr std::array<Field, 4> kBeta = {plain("beta0", 107, 8, 0x1p11, true), plain("beta1", 121, 8, 0x1p14, true),
                                        plain("beta2", 129, 8, 0x1p16, true), plain("beta3", 137, 8, 0x1p16, true)};
constexpr Field kA1 = plain("A1", 151, 24, 0x1p-50, true);
constexpr Field kA0 = split("A0", 181, 24, 211, 32, 0x1p-30, true);
constexpr Field kTot = plain("tot", 219, 8, 4096.0);
constexpr Field kWnt = plain("WNt", 227, 8);
constexpr Field kDeltaTls = plain("delta tLS", 241, 8, 1.0, true);
constexpr Field kWnLsf = plain("WNLSF", 249, 8);
constexpr Field kDn = plain("DN", 257, 8);
constexpr Field kDeltaTlsf = plain("delta tLSF", 271, 8, 1.0, true);
constexpr int kPage18ReservedFirst = 279, kPage18ReservedBits = 14;

// Subframe 5 page 25: toa, WNa, 6-bit health of SVs 1-24 (four per word, words 4-9).
constexpr Field kP25Toa = plain("toa", 69, 8, 4096.0);
constexpr Field kP25Wna = plain("WNa", 77, 8);
int sf5_health_bit(int prn) { return 30 * (3 + (prn - 1) / 4) + 1 + 6 * ((prn - 1) % 4); }
// Subframe 4 page 25: 4-bit A-S/configuration of SVs 1-32 (4 in word 3, then 6 per word),
// 2 reserved bits, then 6-bit health of SVs 25-32 from bit 229, 4 reserved bits at the end.
int sf4_config_bit(int prn) {
  return prn <= 4 ? 69 + 4 * (prn - 1) : 30 * (3 + (prn - 5) / 6) + 1 + 4 * ((prn - 5) % 6);
}
int sf4_health_bit(int prn) {
  if (prn == 25) return 229;
  return prn <= 29 ? 241 + 6 * (prn - 26) : 271 + 6 * (prn - 30);
}

// Alternating ones and zeros (starting with one) over the data bits of words 3-10 from
// subframe bit `first` on, skipping parity and the t bits: the fill of spare, reserved and
// dummy-SV data.
void fill_alternating(DataWords& d, int first, int last = 292) {
  int phase = 1;
  for (int b = first; b <= last; ++b) {
    if ((b - 1) % kBitsPerWord >= 24) continue;
    put_bits(d, b, 1, static_cast<std::uint64_t>(phase));
    phase ^= 1;
  }
}

// ---- Page layout (Table 20-V) ----
constexpr std::array<int, 25> kSf4SvIds = {57, 25, 26, 27, 28, 57, 29, 30, 31, 32, 57, 62, 52,
                                           53, 54, 57, 55, 56, 58, 59, 57, 60, 61, 62, 63};

void check_page(int subframe_id, int page) {
  if (page < 1 || page > kPagesPerCycle) {
    throw std::invalid_argument(fmt::format("LNAV subframe {}: page {} is not in 1..25", subframe_id, page));
  }
}

// ---- Subframe bodies ----
void fill_tlm_how(DataWords& d, int subframe_id, const LnavContent& c, int tow_count_next) {
  TlmHow th;
  th.tlm_message = c.tlm_message;
  th.integrity_flag = c.integrity_flag;
  th.tow_count = tow_count_next;
  th.alert = c.alert;
  th.anti_spoof = c.anti_spoof;
  th.subframe_id = subframe_id;
  const auto words = tlm_how_data(th);
  d[0] = words[0];
  d[1] = words[1];
}

void fill_subframe1(DataWords& d, const Ephemeris& e, int transmission_week) {
  encode_value(d, kWn, ((transmission_week % 1024) + 1024) % 1024, 1);
  encode_value(d, kCodeOnL2, e.code_on_l2, 1);
  encode_value(d, kUra, e.ura_index, 1);
  encode_value(d, kHealth, e.health, 1);
  encode_value(d, kIodc, e.iodc, 1);
  encode_value(d, kL2p, e.l2p_data_flag, 1);
  for (const auto& [first, n] : kSf1Reserved) fill_alternating(d, first, first + n - 1);
  encode_value(d, kTgd, e.tgd_s, 1);
  encode_value(d, kToc, e.toc_s, 1);
  encode_value(d, kAf2, e.af2_sps2, 1);
  encode_value(d, kAf1, e.af1_sps, 1);
  encode_value(d, kAf0, e.af0_s, 1);
}

void fill_subframe2(DataWords& d, const Ephemeris& e) {
  encode_value(d, kIode2, e.iode, 2);
  encode_value(d, kCrs, e.crs_m, 2);
  encode_value(d, kDeltaN, e.delta_n_radps, 2);
  encode_value(d, kM0, e.m0_rad, 2);
  encode_value(d, kCuc, e.cuc_rad, 2);
  encode_value(d, kE, e.e, 2);
  encode_value(d, kCus, e.cus_rad, 2);
  encode_value(d, kSqrtA, e.sqrt_a, 2);
  encode_value(d, kToe, e.toe_s, 2);
  encode_value(d, kFit, e.fit_interval_flag, 2);
  encode_value(d, kAodo, e.aodo_s, 2);
}

void fill_subframe3(DataWords& d, const Ephemeris& e) {
  encode_value(d, kCic, e.cic_rad, 3);
  encode_value(d, kOmega0, e.omega0_rad, 3);
  encode_value(d, kCis, e.cis_rad, 3);
  encode_value(d, kI0, e.i0_rad, 3);
  encode_value(d, kCrc, e.crc_m, 3);
  encode_value(d, kOmega, e.omega_rad, 3);
  encode_value(d, kOmegaDot, e.omega_dot_radps, 3);
  encode_value(d, kIode3, e.iode, 3);
  encode_value(d, kIdot, e.idot_radps, 3);
}

void fill_almanac_page(DataWords& d, int subframe_id, int prn, const std::optional<Almanac>& alm) {
  write_raw(d, kDataId, kDataIdLnav);
  if (!alm) {  // dummy SV: ID 0 and alternating ones and zeros (20.3.3.5.1.2)
    write_raw(d, kSvId, 0);
    fill_alternating(d, kFirstPageDataBit);
    return;
  }
  write_raw(d, kSvId, static_cast<std::uint64_t>(prn));
  encode_value(d, kAlmE, alm->e, subframe_id);
  encode_value(d, kAlmToa, alm->toa_s, subframe_id);
  encode_value(d, kAlmDeltaI, alm->delta_i_rad, subframe_id);
  encode_value(d, kAlmOmegaDot, alm->omega_dot_radps, subframe_id);
  encode_value(d, kAlmHealth, alm->health, subframe_id);
  encode_value(d, kAlmSqrtA, alm->sqrt_a, subframe_id);
  encode_value(d, kAlmOmega0, alm->omega0_rad, subframe_id);
  encode_value(d, kAlmOmega, alm->omega_rad, subframe_id);
  encode_value(d, kAlmM0, alm->m0_rad, subframe_id);
  encode_value(d, kAlmAf0, alm->af0_s, subframe_id);
  encode_value(d, kAlmAf1, alm->af1_sps, subframe_id);
}

void fill_iono_utc_page(DataWords& d, const LnavContent& c) {
  for (int i = 0; i < 4; ++i) {
    encode_value(d, kAlpha[i], c.iono.alpha[i], 4);
    encode_value(d, kBeta[i], c.iono.beta[i], 4);
  }
  encode_value(d, kA1, c.utc.a1_sps, 4);
  encode_value(d, kA0, c.utc.a0_s, 4);
  encode_value(d, kTot, c.utc.tot_s, 4);
  encode_value(d, kWnt, c.utc.wnt & 0xFF, 4);
  encode_value(d, kDeltaTls, c.utc.delta_t_ls, 4);
  encode_value(d, kWnLsf, c.utc.wn_lsf & 0xFF, 4);
  encode_value(d, kDn, c.utc.dn, 4);
  encode_value(d, kDeltaTlsf, c.utc.delta_t_lsf, 4);
  fill_alternating(d, kPage18ReservedFirst, kPage18ReservedFirst + kPage18ReservedBits - 1);
}

int health6_of(const LnavContent& c, int prn) {
  const auto& alm = c.almanac[prn - 1];
  // No almanac: 111111, "SV does not exist" in the 6-bit page-25 health (20.3.3.5.1.3).
  return alm ? (alm->health >> 2 & 0x20) | (alm->health & 0x1F) : 0x3F;
}

void fill_sf4_page25(DataWords& d, const LnavContent& c) {
  for (int prn = 1; prn <= 32; ++prn) {
    encode_value(d, plain("A-S/SV configuration", sf4_config_bit(prn), 4), c.sv_config[prn - 1] & 0xF, 4);
  }
  fill_alternating(d, 227, 228);
  for (int prn = 25; prn <= 32; ++prn)
    encode_value(d, plain("SV health", sf4_health_bit(prn), 6), health6_of(c, prn), 4);
  fill_alternating(d, 289, 292);
}

void fill_sf5_page25(DataWords& d, const LnavContent& c) {
  encode_value(d, kP25Toa, c.almanac_toa_s, 5);
  encode_value(d, kP25Wna, ((c.almanac_week % 256) + 256) % 256, 5);
  for (int prn = 1; prn <= 24; ++prn)
    encode_value(d, plain("SV health", sf5_health_bit(prn), 6), health6_of(c, prn), 5);
  fill_alternating(d, 271, 292);
}

void fill_subframe45(DataWords& d, int subframe_id, int page, const LnavContent& c) {
  const int sv_id = page_sv_id(subframe_id, page);
  if (sv_id >= 1 && sv_id <= 32) {
    fill_almanac_page(d, subframe_id, sv_id, c.almanac[sv_id - 1]);
    return;
  }
  write_raw(d, kDataId, kDataIdLnav);
  write_raw(d, kSvId, static_cast<std::uint64_t>(sv_id));
  if (subframe_id == 5) {
    fill_sf5_page25(d, c);
  } else if (sv_id == 56) {
    fill_iono_utc_page(d, c);
  } else if (sv_id == 63) {
    fill_sf4_page25(d, c);
  } else {
    fill_alternating(d, kFirstPageDataBit);  // reserved, NMCT, special-message pages
  }
}

// ---- Decoding ----
Almanac decode_almanac(const DataWords& d, int prn) {
  Almanac a;
  a.prn = prn;
  a.e = decode_value(d, kAlmE);
  a.toa_s = decode_int(d, kAlmToa);
  a.delta_i_rad = decode_value(d, kAlmDeltaI);
  a.omega_dot_radps = decode_value(d, kAlmOmegaDot);
  a.health = decode_int(d, kAlmHealth);
  a.sqrt_a = decode_value(d, kAlmSqrtA);
  a.omega0_rad = decode_value(d, kAlmOmega0);
  a.omega_rad = decode_value(d, kAlmOmega);
  a.m0_rad = decode_value(d, kAlmM0);
  a.af0_s = decode_value(d, kAlmAf0);
  a.af1_sps = decode_value(d, kAlmAf1);
  return a;
}

void decode_subframe1(const DataWords& d, Ephemeris& e) {
  e.week = decode_int(d, kWn);
  e.code_on_l2 = decode_int(d, kCodeOnL2);
  e.ura_index = decode_int(d, kUra);
  e.health = decode_int(d, kHealth);
  e.iodc = decode_int(d, kIodc);
  e.l2p_data_flag = decode_int(d, kL2p);
  e.tgd_s = decode_value(d, kTgd);
  e.toc_s = decode_value(d, kToc);
  e.af2_sps2 = decode_value(d, kAf2);
  e.af1_sps = decode_value(d, kAf1);
  e.af0_s = decode_value(d, kAf0);
}

void decode_subframe2(const DataWords& d, Ephemeris& e) {
  e.iode = decode_int(d, kIode2);
  e.crs_m = decode_value(d, kCrs);
  e.delta_n_radps = decode_value(d, kDeltaN);
  e.m0_rad = decode_value(d, kM0);
  e.cuc_rad = decode_value(d, kCuc);
  e.e = decode_value(d, kE);
  e.cus_rad = decode_value(d, kCus);
  e.sqrt_a = decode_value(d, kSqrtA);
  e.toe_s = decode_value(d, kToe);
  e.fit_interval_flag = decode_int(d, kFit);
  e.aodo_s = decode_value(d, kAodo);
}

void decode_subframe3(const DataWords& d, Ephemeris& e) {
  e.cic_rad = decode_value(d, kCic);
  e.omega0_rad = decode_value(d, kOmega0);
  e.cis_rad = decode_value(d, kCis);
  e.i0_rad = decode_value(d, kI0);
  e.crc_m = decode_value(d, kCrc);
  e.omega_rad = decode_value(d, kOmega);
  e.omega_dot_radps = decode_value(d, kOmegaDot);
  e.iode = decode_int(d, kIode3);
  e.idot_radps = decode_value(d, kIdot);
}

void decode_iono_utc(const DataWords& d, DecodedSubframe& out) {
  IonoParameters iono;
  for (int i = 0; i < 4; ++i) {
    iono.alpha[i] = decode_value(d, kAlpha[i]);
    iono.beta[i] = decode_value(d, kBeta[i]);
  }
  iono.valid = true;
  UtcParameters utc;
  utc.a1_sps = decode_value(d, kA1);
  utc.a0_s = decode_value(d, kA0);
  utc.tot_s = decode_int(d, kTot);
  utc.wnt = decode_int(d, kWnt);
  utc.delta_t_ls = decode_int(d, kDeltaTls);
  utc.wn_lsf = decode_int(d, kWnLsf);
  utc.dn = decode_int(d, kDn);
  utc.delta_t_lsf = decode_int(d, kDeltaTlsf);
  utc.valid = true;
  out.iono = iono;
  out.utc = utc;
}

void decode_subframe45(const DataWords& d, DecodedSubframe& out) {
  out.data_id = decode_int(d, kDataId);
  out.sv_id = decode_int(d, kSvId);
  const int sf = out.tlm_how.subframe_id;
  if (out.sv_id >= 1 && out.sv_id <= 32) {
    out.almanac = decode_almanac(d, out.sv_id);
  } else if (sf == 5 && out.sv_id == 51) {
    out.almanac_toa_s = decode_int(d, kP25Toa);
    out.almanac_wna = decode_int(d, kP25Wna);
    for (int prn = 1; prn <= 24; ++prn)
      out.sv_health[prn - 1] = decode_int(d, plain("SV health", sf5_health_bit(prn), 6));
  } else if (sf == 4 && out.sv_id == 56) {
    decode_iono_utc(d, out);
  } else if (sf == 4 && out.sv_id == 63) {
    for (int prn = 1; prn <= 32; ++prn)
      out.sv_config[prn - 1] = decode_int(d, plain("A-S/SV configuration", sf4_config_bit(prn), 4));
    for (int prn = 25; prn <= 32; ++prn)
      out.sv_health[prn - 1] = decode_int(d, plain("SV health", sf4_health_bit(prn), 6));
  }
}

double wrap_pi(double a) { return std::remainder(a, 2.0 * gps::kPi); }

// Rounds to the field's LSB the way the encoder does, so a derived almanac equals what a
// receiver decodes from it.
double quantized(double si_value, const Field& f) { return std::round(si_value / f.unit / f.lsb) * f.lsb * f.unit; }

}  // namespace

std::array<std::uint32_t, 2> tlm_how_data(const TlmHow& th) {
  DataWords d{};
  write_raw(d, kPreambleField, kPreamble);
  encode_value(d, kTlmMessage, th.tlm_message, th.subframe_id);
  write_raw(d, kIntegrity, th.integrity_flag ? 1 : 0);
  write_raw(d, kTlmReserved, th.tlm_reserved ? 1 : 0);
  if (th.tow_count < 0 || th.tow_count >= kTowCountsPerWeek) {
    throw std::invalid_argument(fmt::format("LNAV subframe {} HOW: TOW count {} is not in 0..{}", th.subframe_id,
                                            th.tow_count, kTowCountsPerWeek - 1));
  }
  write_raw(d, kTow, static_cast<std::uint64_t>(th.tow_count));
  write_raw(d, kAlert, th.alert ? 1 : 0);
  write_raw(d, kAntiSpoof, th.anti_spoof ? 1 : 0);
  encode_value(d, kSubframeId, th.subframe_id, th.subframe_id);
  return {d[0], d[1]};
}

TlmHow tlm_how_from_data(std::uint32_t tlm_data24, std::uint32_t how_data24) {
  DataWords d{};
  d[0] = tlm_data24 & kDataMask;
  d[1] = how_data24 & kDataMask;
  TlmHow th;
  th.tlm_message = decode_int(d, kTlmMessage);
  th.integrity_flag = decode_int(d, kIntegrity) != 0;
  th.tlm_reserved = decode_int(d, kTlmReserved) != 0;
  th.tow_count = decode_int(d, kTow);
  th.alert = decode_int(d, kAlert) != 0;
  th.anti_spoof = decode_int(d, kAntiSpoof) != 0;
  th.subframe_id = decode_int(d, kSubframeId);
  return th;
}

Subframe encode_words(const SubframeData& data, bool prev_d29, bool prev_d30) {
  Subframe words{};
  bool d29 = prev_d29, d30 = prev_d30;
  for (int w = 0; w < 10; ++w) {
    const std::uint32_t d = (w == 1 || w == 9) ? with_noninformation_bits(data[w], d29, d30) : data[w];
    words[w] = encode_word(d, d29, d30);
    d29 = word_d29(words[w]);
    d30 = word_d30(words[w]);
  }
  return words;
}

int subframe_id_at(std::int64_t subframe_of_week) { return static_cast<int>(((subframe_of_week % 5) + 5) % 5) + 1; }

int page_at(std::int64_t subframe_of_week) {
  const std::int64_t frame = (subframe_of_week >= 0 ? subframe_of_week : subframe_of_week - 4) / 5;
  return static_cast<int>(((frame % kPagesPerCycle) + kPagesPerCycle) % kPagesPerCycle) + 1;
}

int page_sv_id(int subframe_id, int page) {
  check_page(subframe_id, page);
  if (subframe_id == 5) return page == 25 ? 51 : page;
  if (subframe_id == 4) return kSf4SvIds[page - 1];
  throw std::invalid_argument(fmt::format("LNAV: subframe {} has no pages (only 4 and 5 do)", subframe_id));
}

Subframe encode_subframe(int subframe_id, const LnavContent& content, int tow_count_next, int page, bool prev_d29,
                         bool prev_d30) {
  if (subframe_id < 1 || subframe_id > 5) {
    throw std::invalid_argument(fmt::format("LNAV: subframe ID {} is not in 1..5", subframe_id));
  }
  DataWords d{};
  fill_tlm_how(d, subframe_id, content, tow_count_next);
  switch (subframe_id) {
    case 1:
      fill_subframe1(d, content.eph, content.transmission_week.value_or(content.eph.week));
      break;
    case 2:
      fill_subframe2(d, content.eph);
      break;
    case 3:
      fill_subframe3(d, content.eph);
      break;
    default:
      fill_subframe45(d, subframe_id, page, content);
      break;
  }
  return encode_words(d, prev_d29, prev_d30);
}

Subframe subframe_of_week(const LnavContent& content, std::int64_t subframe_of_week) {
  const std::int64_t k = ((subframe_of_week % kTowCountsPerWeek) + kTowCountsPerWeek) % kTowCountsPerWeek;
  const int tow_next = static_cast<int>((k + 1) % kTowCountsPerWeek);
  return encode_subframe(subframe_id_at(k), content, tow_next, page_at(k));
}

std::vector<std::uint8_t> lnav_bits(const LnavContent& content, std::int64_t first_bit, int n_bits) {
  std::vector<std::uint8_t> out;
  out.reserve(static_cast<std::size_t>(std::max(n_bits, 0)));
  LnavBitSource source(content);
  for (int i = 0; i < n_bits; ++i) out.push_back(static_cast<std::uint8_t>(source.bit_at(first_bit + i)));
  return out;
}

int LnavBitSource::bit_at(std::int64_t bit_of_week) {
  const std::int64_t b = ((bit_of_week % kBitsPerWeek) + kBitsPerWeek) % kBitsPerWeek;
  const std::int64_t k = b / kBitsPerSubframe;
  if (k != cached_subframe_) {
    cached_ = subframe_of_week(content_, k);
    cached_subframe_ = k;
  }
  return subframe_bit(cached_, static_cast<int>(b % kBitsPerSubframe));
}

std::optional<DecodedSubframe> decode_subframe(const Subframe& words) {
  DecodedSubframe out;
  const std::uint32_t preamble = (words[0] >> 22) & 0xFFu;
  if (preamble == (~kPreamble & 0xFFu)) {
    out.inverted = true;
  } else if (preamble != kPreamble) {
    return std::nullopt;
  }
  DataWords d{};
  bool d29 = false, d30 = false;
  for (int w = 0; w < 10; ++w) {
    const std::uint32_t word = (out.inverted ? ~words[w] : words[w]) & kWordMask;
    const auto data = check_word(word, d29, d30);
    if (!data) return std::nullopt;
    d[w] = *data;
    d29 = word_d29(word);
    d30 = word_d30(word);
  }
  out.data = d;
  out.tlm_how = tlm_how_from_data(d[0], d[1]);
  const auto& th = out.tlm_how;
  if (th.subframe_id < 1 || th.subframe_id > 5 || th.tow_count >= kTowCountsPerWeek) return std::nullopt;
  out.sv_health.fill(-1);
  out.sv_config.fill(-1);
  const int start_count = (th.tow_count + kTowCountsPerWeek - 1) % kTowCountsPerWeek;
  switch (th.subframe_id) {
    case 1:
      decode_subframe1(d, out.eph);
      break;
    case 2:
      decode_subframe2(d, out.eph);
      break;
    case 3:
      decode_subframe3(d, out.eph);
      break;
    default:
      out.page = page_at(start_count);
      decode_subframe45(d, out);
      break;
  }
  return out;
}

std::optional<DecodedSubframe> decode_partial_subframe(int subframe_id, int tow_count,
                                                       const PartialSubframeData& words) {
  if (subframe_id < 1 || subframe_id > 3 || tow_count < 0 || tow_count >= kTowCountsPerWeek) return std::nullopt;
  // Word indices (0-based) each subframe's ephemeris fields lie in; word 3 of subframe 1 is
  // optional (its week comes from any satellite, or the receiver's reference).
  const int first_needed = subframe_id == 1 ? 6 : 2;
  for (int w = first_needed; w < 10; ++w)
    if (!words[static_cast<std::size_t>(w)]) return std::nullopt;
  DecodedSubframe out;
  DataWords d{};
  for (int w = 0; w < 10; ++w) d[static_cast<std::size_t>(w)] = words[static_cast<std::size_t>(w)].value_or(0u);
  out.data = d;
  out.tlm_how.tow_count = tow_count;
  out.tlm_how.subframe_id = subframe_id;
  out.sv_health.fill(-1);
  out.sv_config.fill(-1);
  switch (subframe_id) {
    case 1:
      decode_subframe1(d, out.eph);
      out.week_received = words[2].has_value();
      break;
    case 2:
      decode_subframe2(d, out.eph);
      break;
    default:
      decode_subframe3(d, out.eph);
      break;
  }
  return out;
}

std::optional<int> issue_of_data_in_word(int subframe_id, int word_index, std::uint32_t data24) {
  if (word_index < 0 || word_index > 9) return std::nullopt;
  DataWords d{};
  d[static_cast<std::size_t>(word_index)] = data24;
  if (subframe_id == 1 && word_index == 7) return decode_int(d, kIodc) & 0xFF;  // the 2 MSBs are in word 3
  if (subframe_id == 2 && word_index == 2) return decode_int(d, kIode2);
  if (subframe_id == 3 && word_index == 9) return decode_int(d, kIode3);
  return std::nullopt;
}

int week_number_in_word3(std::uint32_t data24) {
  DataWords d{};
  d[2] = data24;
  return decode_int(d, kWn);
}

Almanac almanac_from_ephemeris(const Ephemeris& eph) {
  constexpr int kToaLsb = 4096, kMaxToaCount = 147;  // toa: 8 bits of 4096 s within 602112 s
  Almanac a;
  a.prn = eph.prn;
  a.week = eph.week;
  a.toa_s = kToaLsb * std::clamp(static_cast<int>(std::lround(eph.toe_s / kToaLsb)), 0, kMaxToaCount);
  const double dt_toe = a.toa_s - eph.toe_s;
  const double dt_toc = seconds_of_week_difference(a.toa_s, eph.toc_s);
  const double a_m = eph.sqrt_a * eph.sqrt_a;
  const double n_radps = std::sqrt(gps::kGM_m3ps2 / (a_m * a_m * a_m)) + eph.delta_n_radps;
  a.e = quantized(eph.e, kAlmE);
  a.sqrt_a = quantized(eph.sqrt_a, kAlmSqrtA);
  a.delta_i_rad = quantized(eph.i0_rad + eph.idot_radps * dt_toe - kAlmanacNominalInclination_rad, kAlmDeltaI);
  a.omega_dot_radps = quantized(eph.omega_dot_radps, kAlmOmegaDot);
  // Same node longitude at every t: OMEGA0_alm = OMEGA0 + OMEGADOT (toa - toe).
  a.omega0_rad = quantized(wrap_pi(eph.omega0_rad + eph.omega_dot_radps * dt_toe), kAlmOmega0);
  a.omega_rad = quantized(wrap_pi(eph.omega_rad), kAlmOmega);
  a.m0_rad = quantized(wrap_pi(eph.m0_rad + n_radps * dt_toe), kAlmM0);
  a.af0_s = quantized(eph.af0_s + eph.af1_sps * dt_toc + eph.af2_sps2 * dt_toc * dt_toc, kAlmAf0);
  a.af1_sps = quantized(eph.af1_sps + 2.0 * eph.af2_sps2 * dt_toc, kAlmAf1);
  // 8-bit health: the 6-bit word's NAV-data summary bit becomes "all data bad" (111) in the
  // three NAV-data bits; the five signal-component bits are the same.
  a.health = ((eph.health & 0x20) ? 0xE0 : 0) | (eph.health & 0x1F);
  return a;
}

FieldLimits field_limits(std::string_view name) {
  static const std::array<const Field*, 29> kFields = {
      &kAf0,      &kAf1,      &kAf2,      &kTgd,     &kCrs,     &kDeltaN,  &kM0,      &kCuc,      &kE,    &kCus,
      &kSqrtA,    &kCic,      &kOmega0,   &kCis,     &kI0,      &kCrc,     &kOmega,   &kOmegaDot, &kIdot, &kAlpha[0],
      &kAlpha[1], &kAlpha[2], &kAlpha[3], &kBeta[0], &kBeta[1], &kBeta[2], &kBeta[3], &kA0,       &kA1};
  for (const Field* f : kFields) {
    if (name != f->name) continue;
    const double lo = f->is_signed ? -std::ldexp(1.0, f->bits - 1) : 0.0;
    const double hi = f->is_signed ? std::ldexp(1.0, f->bits - 1) - 1.0 : std::ldexp(1.0, f->bits) - 1.0;
    return {lo * f->lsb * f->unit, hi * f->lsb * f->unit};
  }
  throw std::invalid_argument(fmt::format("LNAV: no broadcast field named '{}'", name));
}

int resolve_week(int wn10, int reference_week) {
  const int base = reference_week - ((reference_week % 1024) + 1024) % 1024;
  int week = base + (wn10 & 0x3FF);
  if (week - reference_week > 512) week -= 1024;
  if (reference_week - week > 512) week += 1024;
  return week;
}

bool EphemerisAssembler::add(const DecodedSubframe& sf) {
  switch (sf.tlm_how.subframe_id) {
    case 1:
      sf1_ = sf;
      break;
    case 2:
      sf2_ = sf;
      break;
    case 3:
      sf3_ = sf;
      break;
    case 4:
      if (sf.iono) iono_ = *sf.iono;
      if (sf.utc) utc_ = *sf.utc;
      return false;
    default:
      return false;
  }
  return try_complete();
}

bool EphemerisAssembler::try_complete() {
  if (!sf1_ || !sf2_ || !sf3_) return false;
  const int iode2 = sf2_->eph.iode, iode3 = sf3_->eph.iode;
  if (iode2 != iode3 || (sf1_->eph.iodc & 0xFF) != iode2) return false;
  const Ephemeris& s1 = sf1_->eph;
  const Ephemeris& s2 = sf2_->eph;
  const Ephemeris& s3 = sf3_->eph;
  Ephemeris e = s1;  // clock and subframe 1 fields
  e.prn = prn_;
  // Without subframe 1's word 3 the reference week stands in: the receiver dates nothing by
  // it (its clock waits for a broadcast or given week), and ephemeris ages fold across the
  // week boundary when it is off (seconds_from_reference).
  e.week = sf1_->week_received ? resolve_week(s1.week, reference_week_) : reference_week_;
  e.iode = iode2;
  e.crs_m = s2.crs_m;
  e.delta_n_radps = s2.delta_n_radps;
  e.m0_rad = s2.m0_rad;
  e.cuc_rad = s2.cuc_rad;
  e.e = s2.e;
  e.cus_rad = s2.cus_rad;
  e.sqrt_a = s2.sqrt_a;
  e.toe_s = s2.toe_s;
  e.fit_interval_flag = s2.fit_interval_flag;
  e.aodo_s = s2.aodo_s;
  e.cic_rad = s3.cic_rad;
  e.omega0_rad = s3.omega0_rad;
  e.cis_rad = s3.cis_rad;
  e.i0_rad = s3.i0_rad;
  e.crc_m = s3.crc_m;
  e.omega_rad = s3.omega_rad;
  e.omega_dot_radps = s3.omega_dot_radps;
  e.idot_radps = s3.idot_radps;
  // Subframe 1 starts one TOW count (6 s) before the count its HOW carries.
  e.transmission_time_s = 6.0 * ((sf1_->tlm_how.tow_count + kTowCountsPerWeek - 1) % kTowCountsPerWeek);
  // WN is the week subframe 1 was sent in; toe may lie in the week after it (a data set cut
  // over at the week's end) or before it (one sent on after the boundary). Ephemeris::week
  // is toe's: the one that puts toe within half a week of the transmission.
  const double toe_after_transmission_s = e.toe_s - e.transmission_time_s;
  if (toe_after_transmission_s > kSecondsPerWeek / 2) e.week -= 1;
  if (toe_after_transmission_s < -kSecondsPerWeek / 2) e.week += 1;
  const bool is_new = !ephemeris_ || ephemeris_->iodc != e.iodc || ephemeris_->iode != e.iode ||
                      ephemeris_->toe_s != e.toe_s || ephemeris_->week != e.week;
  ephemeris_ = e;
  return is_new;
}

}  // namespace deepnav::lnav
