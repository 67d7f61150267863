#pragma once
// LNAV navigation message (IS-GPS-200 20.3.2 - 20.3.5): encoding of the five 300-bit subframes
// and the 25-page cycle of subframes 4 and 5 into the bit stream a satellite transmits, and
// decoding of received subframes back into ephemeris, almanac, ionosphere and UTC data.
//
// Bit numbering follows the spec: subframe bits 1..300, word bit 1 sent first. A word is a
// uint32 whose bits 29..0 are word bits 1..30, parity applied, polarity as transmitted.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "signals/ephemeris.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav::lnav {

using Subframe = std::array<std::uint32_t, 10>;
/// Source data d1..d24 of the ten words of a subframe (d1 at bit 23), before parity and
/// before the D30* complementing of the transmitted word.
using SubframeData = std::array<std::uint32_t, 10>;

inline constexpr int kBitsPerWord = 30;
inline constexpr int kBitsPerSubframe = 300;
inline constexpr int kPagesPerCycle = 25;
inline constexpr std::uint32_t kPreamble = 0x8B;
inline constexpr int kTowCountsPerWeek = 100800;  ///< HOW TOW counts (6 s) in a week
inline constexpr std::int64_t kBitsPerWeek = std::int64_t{kTowCountsPerWeek} * kBitsPerSubframe;
inline constexpr double kAlmanacNominalInclination_rad = 0.30 * 3.1415926535898;  ///< Table 20-VI note

/// Reduced-precision orbit and clock of one SV (IS-GPS-200 Table 20-VI). Angles in radians.
struct Almanac {
  int prn = 0;     ///< SV ID 1..32
  int health = 0;  ///< 8-bit health word (3 MSBs NAV data, 5 LSBs signal components)
  double e = 0.0;
  int toa_s = 0;             ///< almanac reference time, multiple of 4096 s
  int week = 0;              ///< full almanac reference week (WNa in the message: 8 LSBs)
  double delta_i_rad = 0.0;  ///< inclination relative to 0.30 semicircles
  double omega_dot_radps = 0.0;
  double sqrt_a = 0.0;
  double omega0_rad = 0.0;
  double omega_rad = 0.0;
  double m0_rad = 0.0;
  double af0_s = 0.0;
  double af1_sps = 0.0;
};

/// TLM and HOW words (IS-GPS-200 20.3.3.1, 20.3.3.2).
struct TlmHow {
  int tlm_message = 0;          ///< 14 bits
  bool integrity_flag = false;  ///< TLM bit 23
  bool tlm_reserved = false;    ///< TLM bit 24
  int tow_count = 0;            ///< 17-bit truncated TOW count of the next subframe start (6 s units)
  bool alert = false;
  bool anti_spoof = false;
  int subframe_id = 0;  ///< 1..5
};

/// Everything one satellite broadcasts. Subframe 1's week number (WN) is the week the
/// subframe is sent in, modulo 1024 (IS-GPS-200 20.3.3.3.1.1): transmission_week when set,
/// else eph.week (toe's week, which is the week of transmission but for an ephemeris sent
/// across a week boundary).
struct LnavContent {
  Ephemeris eph;
  std::optional<int> transmission_week;  ///< full GPS week the message is sent in
  IonoParameters iono;
  UtcParameters utc;
  std::array<std::optional<Almanac>, 32> almanac;  ///< by PRN - 1; empty: dummy SV page
  int almanac_toa_s = 0;                           ///< toa of subframe 5 page 25
  int almanac_week = 0;                            ///< full week; WNa of subframe 5 page 25 is its 8 LSBs
  std::array<std::uint8_t, 32> sv_config{};        ///< 4-bit A-S flag and configuration per SV
  int tlm_message = 0;
  bool integrity_flag = false;
  bool alert = false;
  bool anti_spoof = false;
};

/// Subframe and page that start at a given subframe count of the week.
int subframe_id_at(std::int64_t subframe_of_week);
int page_at(std::int64_t subframe_of_week);

/// Data ID and SV ID (page ID) of a page of subframe 4 or 5 (IS-GPS-200 Table 20-V).
int page_sv_id(int subframe_id, int page);

/// Encodes subframe 1..5. tow_count_next is the HOW TOW count (start of the next subframe);
/// page (1..25) matters for subframes 4 and 5 only. prev_d29/prev_d30 are the last two bits of
/// the previous subframe (both 0 in a continuous stream, which word 10's t bits guarantee).
/// Throws std::invalid_argument naming the field when a value does not fit its bit field.
Subframe encode_subframe(int subframe_id, const LnavContent& content, int tow_count_next, int page,
                         bool prev_d29 = false, bool prev_d30 = false);

/// Parity and polarity of a subframe from its source data (20.3.5): each word is encoded with the
/// D29*, D30* of the word before it (prev_d29/prev_d30 for word 1), and the non-information
/// bits d23, d24 of words 2 and 10 are set so that those words end in D29 = D30 = 0 (whatever
/// `data` holds there is replaced). So word 3 never depends on the HOW's content and word 1
/// never on the previous subframe's.
Subframe encode_words(const SubframeData& data, bool prev_d29 = false, bool prev_d30 = false);

/// Source data of the TLM and HOW words (words 1 and 2) carrying these fields; the HOW's d23,
/// d24 are left 0 (encode_words sets them). Throws std::invalid_argument naming the field when
/// a value does not fit (TLM message 14 bits, TOW count 0..100799, subframe ID 3 bits).
std::array<std::uint32_t, 2> tlm_how_data(const TlmHow& tlm_how);

/// The fields of TLM and HOW source data (the inverse of tlm_how_data; the preamble is not
/// checked here).
TlmHow tlm_how_from_data(std::uint32_t tlm_data24, std::uint32_t how_data24);

/// The subframe a satellite transmits starting at subframe count k of the week (bits 300k ...).
Subframe subframe_of_week(const LnavContent& content, std::int64_t subframe_of_week);

/// Bit i (0 first, 0/1) of a subframe as transmitted.
inline int subframe_bit(const Subframe& sf, int bit_index) {
  return static_cast<int>((sf[bit_index / kBitsPerWord] >> (kBitsPerWord - 1 - bit_index % kBitsPerWord)) & 1u);
}

/// n_bits consecutive data bits (0/1) starting at bit index first_bit counted from the week
/// start (20 ms bits); indices beyond the week wrap into the next week's TOW.
std::vector<std::uint8_t> lnav_bits(const LnavContent& content, std::int64_t first_bit, int n_bits);

/// Single bit at a week bit index, with the subframe it falls in cached, so that a caller
/// stepping through the stream encodes each subframe once. One cache per satellite.
class LnavBitSource {
 public:
  explicit LnavBitSource(LnavContent content) : content_(std::move(content)) {}
  int bit_at(std::int64_t bit_of_week);
  const LnavContent& content() const { return content_; }

 private:
  LnavContent content_;
  std::int64_t cached_subframe_ = -1;
  Subframe cached_{};
};

/// A subframe checked and decoded. Fields of the other subframe types keep their defaults.
struct DecodedSubframe {
  TlmHow tlm_how;
  SubframeData data{};    ///< d1..d24 of every word, polarity and complementing undone
  bool inverted = false;  ///< the stream arrived with inverted polarity
  int page = 0;           ///< 1..25 for subframes 4 and 5, from the TOW count
  /// Subframes 1-3: the fields they carry. eph.week holds the 10-bit WN of subframe 1.
  Ephemeris eph;
  int data_id = 0, sv_id = 0;      ///< subframes 4 and 5
  std::optional<Almanac> almanac;  ///< almanac pages (week = 0: WNa comes from subframe 5 page 25)
  std::optional<IonoParameters> iono;
  std::optional<UtcParameters> utc;
  std::optional<int> almanac_toa_s, almanac_wna;  ///< subframe 5 page 25
  std::array<int, 32> sv_health{};                ///< 6-bit health by PRN - 1 from page 25; -1 absent
  std::array<int, 32> sv_config{};                ///< 4-bit A-S/config by PRN - 1 (subframe 4 page 25); -1 absent
  /// Subframe 1: word 3 (week number, URA, health, IODC's 2 MSBs) was received. A subframe
  /// decoded from its clock words alone (decode_partial_subframe) leaves those fields 0.
  bool week_received = true;
};

/// Checks every word's parity (D29*, D30* of word 1 taken as 0, the value word 10's t bits
/// give), resolves the polarity from the preamble and extracts all fields. nullopt when the
/// preamble is missing, a parity check fails or the subframe ID is not 1..5.
std::optional<DecodedSubframe> decode_subframe(const Subframe& words);

/// Source data d1..d24 of the words of a subframe received in part (each word checked on its
/// own parity); empty where a word was not received or failed parity.
using PartialSubframeData = std::array<std::optional<std::uint32_t>, 10>;

/// Subframe 1, 2 or 3 from the words received of a copy whose start (TLM, HOW) was missed:
/// the subframe ID and HOW TOW count come from the channel's time instead. Subframes 2 and 3
/// need words 3-10 (every orbit field and the IODE); subframe 1 its clock words 7-10 (TGD,
/// IODC's 8 LSBs, toc, af2, af1, af0), word 3 being taken where received (week_received).
/// nullopt for another subframe ID or when a needed word is missing.
std::optional<DecodedSubframe> decode_partial_subframe(int subframe_id, int tow_count,
                                                       const PartialSubframeData& words);

/// The issue of data a word of subframe 1, 2 or 3 carries: IODC's 8 LSBs in subframe 1 word
/// 8, IODE in subframe 2 word 3 and subframe 3 word 10 (d1..d8 of each); nullopt for any
/// other word. `word_index` counts from 0.
std::optional<int> issue_of_data_in_word(int subframe_id, int word_index, std::uint32_t data24);

/// The 10-bit week number subframe 1 word 3 carries (d1..d10).
int week_number_in_word3(std::uint32_t data24);

/// Almanac from an ephemeris: elements carried to toa (the multiple of 4096 s nearest toe in
/// the same week) and quantized to the almanac's scale factors.
Almanac almanac_from_ephemeris(const Ephemeris& eph);

/// The values (SI units: s, m, rad, rad/s, s/semicircle^n) an LNAV field can carry: its bit
/// width, sign and scale factor (IS-GPS-200 Tables 20-I, 20-III, 20-IX and 20-X). Every real
/// broadcast lies inside; a navigation file value far outside is corrupt.
struct FieldLimits {
  double min = 0.0;
  double max = 0.0;
};
/// By the field's name as the message layout spells it: "af0", "af1", "af2", "TGD", "Crs",
/// "delta n", "M0", "Cuc", "e", "Cus", "sqrt A", "Cic", "OMEGA0", "Cis", "i0", "Crc", "omega",
/// "OMEGADOT", "IDOT", "alpha0".."alpha3", "beta0".."beta3", "A0", "A1". Throws
/// std::invalid_argument for any other name.
FieldLimits field_limits(std::string_view name);

/// Full week closest to reference_week whose 10 LSBs equal wn10.
int resolve_week(int wn10, int reference_week);

/// Collects decoded subframes of one satellite into an ephemeris once subframes 1, 2 and 3
/// with matching issue of data are in, and subframe 4 page 18 into ionosphere/UTC. The
/// ephemeris's week is toe's: subframe 1's week of transmission (resolved against
/// reference_week), one more or less where toe lies across a week boundary from it.
class EphemerisAssembler {
 public:
  EphemerisAssembler(int prn, int reference_week) : prn_(prn), reference_week_(reference_week) {}

  /// Returns true when this subframe completed a new (different IODE or first) ephemeris.
  bool add(const DecodedSubframe& sf);

  const std::optional<Ephemeris>& ephemeris() const { return ephemeris_; }
  const IonoParameters& iono() const { return iono_; }
  const UtcParameters& utc() const { return utc_; }

 private:
  bool try_complete();

  int prn_;
  int reference_week_;
  std::optional<DecodedSubframe> sf1_, sf2_, sf3_;
  std::optional<Ephemeris> ephemeris_;
  IonoParameters iono_;
  UtcParameters utc_;
};

}  // namespace deepnav::lnav
