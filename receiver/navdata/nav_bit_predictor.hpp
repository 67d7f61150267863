#pragma once
// Navigation-bit prediction (data wipe-off) for one satellite: the LNAV bits it will transmit,
// predicted from what it has transmitted before, so that a channel can remove the data
// modulation and integrate coherently across bit edges.
//
// What LNAV makes predictable (IS-GPS-200 20.3.2 - 20.3.5):
//  - TLM and HOW (words 1-2 of every subframe): the preamble, the TLM message and flags, and
//    the HOW's alert and A-S flags repeat; the TOW count is the next subframe's count, the
//    subframe ID follows the 5-subframe frame, both advancing from the bit's time of week.
//    Subframe 1's WN is the week it is sent in: taken from the absolute bit, not learned.
//  - Subframes 1-3 (words 3-10): the ephemeris and clock data set, repeated every 30 s frame
//    until the next upload (a new IODC/IODE, at a frame boundary).
//  - Subframes 4-5 (words 3-10): the 25-page cycle, 12.5 min, keyed to the TOW count and reset
//    to page 1 at the start of the week (so the last frame of a week carries page 10).
//  - Parity: recomputed from the predicted source data with the LNAV word encoder
//    (lnav::encode_word, lnav::with_noninformation_bits): each word's parity and its
//    complementing depend on D29*, D30* of the word before it, taken from that word's
//    prediction. Words 2 and 10 end in D29 = D30 = 0 by their non-information bits, so word 1
//    and word 3 never depend on the word before them. Where the word before is not known,
//    the D29*, D30* the word was last received with stand in (they repeat with the data).
//
// Knowledge is kept per source-data word: the header's TLM word and HOW flags, and words 3-10
// of each of 53 bodies (subframes 1-3, and subframes 4 and 5 of each page). It comes from
//  - learn(): a subframe the NavDecoder decoded (all ten words parity-checked);
//  - learn_word(): single parity-checked words out of a weak stream (NavBitMonitor);
//  - assist(): subframes 1-3 encoded from a navigation file's ephemeris (optional, before
//    any decode; they are only as good as the file's reproduction of the broadcast: reserved
//    bits, AODO and the fit flag a RINEX record does not carry may differ, and the monitor
//    then marks the subframe unknown and it is learned from the signal instead).
// A bit is unknown (0) when its word's data has not been seen (or, for a HOW, the TLM's);
// the 8 preamble bits of every subframe are always known.
//
// Use in a tracking channel (the interface for long coherent integration; this class changes
// no tracking behaviour by itself):
//   1. bit index: the channel's NavDecoder gives the satellite transmit time of a code period
//      (transmit_time_sow); with the week, nav_bit_index() is the absolute data bit.
//   2. after each bit, if nav.subframes_decoded() grew: predictor.learn(*nav.last_decoded()).
//   3. before integrating over bits [b, b + n): predictor.signs(b, out) with out.size() == n;
//      a run of non-zero signs can be wiped off (multiply each 20 ms prompt sum by its sign,
//      times nav.polarity()) and summed coherently; a 0 ends the coherent span at that bit
//      edge (fall back to bit-edge-limited integration there).
//   4. after each bit: monitor.observe(predictor, b, sign of the bit's prompt sum times
//      nav.polarity(), nav_bit_error_rate(C/N0)) checks the prediction against the signal:
//      a failed prediction (new upload, changed page, wrong assisted word) is detected
//      within a few bits and its body forgotten, then re-learned word by word.
// One predictor and one monitor per channel, used from one thread (the prediction of the
// current subframe is cached).
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "ins/gps_time.hpp"
#include "signals/ephemeris.hpp"
#include "signals/lnav_message.hpp"

namespace deepnav {

/// Absolute index of the 20 ms LNAV data bit transmitted at GPS time t (satellite time),
/// counted from the GPS time origin: bit b spans [b * 20 ms, (b + 1) * 20 ms) and
/// b mod lnav::kBitsPerWeek is its bit of the week. Pass a time well inside the bit (its middle):
/// a time on an edge may round either way.
std::int64_t nav_bit_index(const GpsTime& t);

/// Probability that the sign of a coherent prompt sum over integration_s is wrong with an ideal,
/// phase-locked carrier: Q(sqrt(2 C/N0 T)) = erfc(sqrt(C/N0 T)) / 2. For 20 ms bits: 6e-3 at
/// 22 dB-Hz, 2.3e-2 at 20, 0.13 at 15, 0.26 at 10. Phase jitter makes a real loop's larger.
double nav_bit_error_rate(double cn0_dbhz, double integration_s = 0.02);

class NavBitPredictor {
 public:
  /// Knowledge segments: the header (TLM/HOW of every subframe), the bodies (words 3-10) of
  /// subframes 1, 2, 3 (segments 1..3), of subframe 4 pages 1..25 (4..28) and of subframe 5
  /// pages 1..25 (29..53).
  static constexpr int kHeaderSegment = 0;
  static constexpr int kSegments = 54;
  static int body_segment(int subframe_id, int page);
  /// The segment absolute data bit `bit` belongs to.
  static int segment_of_bit(std::int64_t bit);
  static bool is_ephemeris_segment(int segment) { return segment >= 1 && segment <= 3; }

  /// Where a body's words came from.
  enum class Source : std::uint8_t { none, broadcast, assisted };

  // ---- learning ----
  /// Learns the header and the subframe's body from a decoded subframe. A body of subframes
  /// 1-3 that differs from the one known is a new upload: the other two ephemeris bodies are
  /// forgotten with it (they belong to the old data set and will be re-learned).
  void learn(const lnav::DecodedSubframe& sf);
  /// Learns one parity-checked word (source data d1..d24) of the subframe at `subframe_of_week`
  /// (0 .. kTowCountsPerWeek - 1), word index 0..9. A TLM word is taken only with the preamble,
  /// a HOW only when its TOW count and subframe ID are the ones due at that subframe (returns
  /// false otherwise; how_mismatches() counts HOWs that disagree, a sign of a wrong bit index).
  /// prev_d29/prev_d30: the D29*, D30* the word was received with (ignored for words 1-3).
  bool learn_word(std::int64_t subframe_of_week, int word, std::uint32_t data24, bool prev_d29 = false,
                  bool prev_d30 = false);
  /// Subframes 1-3 from a navigation-file ephemeris, for bodies not already known from the
  /// broadcast; `header` (TLM message and flags, A-S/alert) optionally as an assumption when
  /// the header is not known. Throws std::invalid_argument when a value does not fit LNAV.
  void assist(const Ephemeris& eph, const std::optional<lnav::TlmHow>& header = std::nullopt);
  /// Forgets one segment.
  void forget(int segment);
  /// What a failed prediction in `segment` makes unknown: the header; all three ephemeris
  /// bodies (an upload changes the data set together); or the one page.
  void forget_after_failure(int segment);

  // ---- prediction ----
  /// Sign of absolute data bit `bit`: +1 (bit 0), -1 (bit 1, IS-GPS-200 3.2.2), 0 unknown.
  /// Transmitted polarity: multiply by the channel's polarity to compare with its prompt.
  int sign(std::int64_t bit) const;
  /// Sign of the bit transmitted at GPS time t (satellite time; see nav_bit_index).
  int sign_at(const GpsTime& t) const { return sign(nav_bit_index(t)); }
  /// Signs of bits first_bit, first_bit + 1, ... into out (out.size() bits).
  void signs(std::int64_t first_bit, std::span<std::int8_t> out) const;
  /// Whether the source data of word 0..9 of the subframe at subframe_of_week is known.
  bool word_data_known(std::int64_t subframe_of_week, int word) const;

  // ---- state ----
  bool tlm_known() const { return tlm_known_; }
  bool how_known() const { return how_known_; }
  /// Number of words 3-10 of a body whose data is known (0..8).
  int body_words_known(int segment) const;
  Source source(int segment) const { return bodies_[static_cast<std::size_t>(segment)].source; }
  int how_mismatches() const { return how_mismatches_; }
  int uploads_seen() const { return uploads_; }

 private:
  struct Body {
    std::array<std::uint32_t, 8> data{};  ///< d1..d24 of words 3..10
    std::array<std::uint8_t, 8> chain{};  ///< D29* (bit 1), D30* (bit 0) word 3 + i came with
    std::uint8_t known = 0;               ///< bit i: word 3 + i known
    Source source = Source::none;
  };
  struct Predicted {
    std::int64_t subframe = -1;  ///< absolute subframe (from the GPS time origin), -1: none
    std::uint64_t version = 0;
    lnav::Subframe words{};
    std::uint16_t known = 0;  ///< bit w: word w (0-based) predictable
  };

  /// The words of absolute subframe `subframe` (its week gives subframe 1's WN).
  const Predicted& predicted(std::int64_t subframe) const;
  static void set_chain(Body& body, const lnav::Subframe& words);
  void changed() { ++version_; }

  lnav::TlmHow header_{};
  bool tlm_known_ = false, how_known_ = false;
  std::array<Body, kSegments> bodies_{};  ///< index 0 (the header) unused
  int how_mismatches_ = 0;
  int uploads_ = 0;
  std::uint64_t version_ = 1;
  mutable Predicted cache_;
};

}  // namespace deepnav
