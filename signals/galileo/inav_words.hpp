#pragma once
// The 128-bit words of the Galileo I/NAV message on E1-B (Galileo OS SIS ICD 4.3.5): a 6-bit
// word type, then the type's fields, most significant bit first, two's complement where
// signed. Values are in SI units and radians here, scaled by the ICD's LSBs at the edges.
//
//   type 0     spare word: time flag, week and time of week
//   types 1-4  ephemeris 1/4..4/4 (with IODnav), SISA(E1,E5b), clock (af0..af2, t0c)
//   type 5     NeQuick G ionosphere (a_i0..a_i2, region flags), BGD(E1,E5a), BGD(E1,E5b),
//              E5b/E1-B health and data validity, GST week and time of week
//   type 6     GST-UTC conversion and time of week
//   types 7-10 almanac of three satellites (with IODa); type 10 ends with the GGTO
//   type 63    dummy word
#include <array>
#include <cstdint>
#include <optional>

#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/galileo/gst.hpp"
#include "signals/galileo/nequick_parameters.hpp"
#include "signals/iono_utc.hpp"

namespace deepnav::galileo::inav {

inline constexpr int kWordBits = 128;
inline constexpr int kDummyWordType = 63;
/// A word's bits (0/1), the first transmitted first.
using Word = std::array<std::uint8_t, kWordBits>;

/// Word type 0. time_flag 2 (binary 10) says week and time of week are valid.
struct SpareWord {
  int time_flag = 0;
  int week = 0;  ///< GST week, 12 bits
  int tow_s = 0;
};

/// Word type 5.
struct IonoDelayHealthWord {
  NequickParameters iono;
  double bgd_e1e5a_s = 0.0;
  double bgd_e1e5b_s = 0.0;
  SignalStatus e5b, e1b;
  int week = 0;  ///< GST week, 12 bits
  int tow_s = 0;
};

/// Word type 6: GST-UTC parameters (the fields of GPS's, ICD 5.1.7) and time of week.
struct UtcWord {
  UtcParameters utc;  ///< tot_s a multiple of 3600; wnt, wn_lsf as broadcast (8 bits)
  int tow_s = 0;
};

/// One satellite's almanac (ICD 5.1.10): differences from the nominal orbit, radians.
struct AlmanacEntry {
  int svid = 0;               ///< 0: no satellite in this slot
  double delta_sqrt_a = 0.0;  ///< from sqrt(29 600 km), sqrt(m)
  double e = 0.0;
  double omega_rad = 0.0;
  double delta_i_rad = 0.0;  ///< from 56 degrees
  double omega0_rad = 0.0;
  double omega_dot_radps = 0.0;
  double m0_rad = 0.0;
  double af0_s = 0.0;
  double af1_sps = 0.0;
  int e5b_health = 0;
  int e1b_health = 0;
};

/// Word types 7 to 10: the almanacs of three satellites and, in type 10, the GGTO.
struct AlmanacBatch {
  int iod_a = 0;
  int week = 0;   ///< WNa, 2 bits
  int t0a_s = 0;  ///< multiple of 600 s
  std::array<AlmanacEntry, 3> sv{};
  GgtoParameters ggto;  ///< wn0g as broadcast, 6 bits
};

/// The word type of a word (its first 6 bits).
int word_type(const Word& word);

/// Words 1..4 of an ephemeris. Throws std::invalid_argument naming the field when a value
/// does not fit its field (the week is not in these words; SVID is the PRN).
Word encode_ephemeris_word(int type, const GalileoEphemeris& eph);
Word encode_spare_word(const SpareWord& w);
Word encode_iono_delay_health_word(const IonoDelayHealthWord& w);
Word encode_utc_word(const UtcWord& w);
Word encode_almanac_word(int type, const AlmanacBatch& batch);
Word encode_dummy_word();

/// Reads word 1..4 into the fields of `eph` that it carries and returns its IODnav.
int decode_ephemeris_word(const Word& word, GalileoEphemeris& eph);
SpareWord decode_spare_word(const Word& word);
IonoDelayHealthWord decode_iono_delay_health_word(const Word& word);
UtcWord decode_utc_word(const Word& word);
/// Reads word 7..10 into the fields of `batch` that it carries.
void decode_almanac_word(const Word& word, AlmanacBatch& batch);

/// Collects decoded words into a complete ephemeris: words 1 to 4 of one IODnav and a word 5
/// (group delays, health, GST week). The GST week of word 5 becomes the ephemeris week
/// (toe within half a week of the word's time). Words of another type are ignored.
class EphemerisAssembler {
 public:
  void add(const Word& word);
  /// The ephemeris once all five words are in; nullopt before.
  std::optional<GalileoEphemeris> ephemeris() const;

 private:
  GalileoEphemeris eph_;
  std::array<std::optional<int>, 4> iod_of_word_{};  ///< IODnav of words 1..4 as received
  std::optional<IonoDelayHealthWord> word5_;
};

}  // namespace deepnav::galileo::inav
