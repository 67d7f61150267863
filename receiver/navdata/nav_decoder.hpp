#pragma once
// LNAV data of one channel: data bits from bit-aligned prompt integrations, subframe
// synchronisation (preamble in either polarity, confirmed by every word's parity),
// subframe decoding, ephemeris/ionosphere/UTC assembly, and the time anchor that turns
// a code period count into the satellite's transmit time:
//   t_sv = (HOW TOW count - 1) * 6 s + (period - first period of that subframe) * 1 ms
//          + code phase / 1.023 MHz.
//
// The ephemeris is assembled from single words (EphemerisWords): once the first subframe is
// decoded, the word boundaries and the time of every bit are known, so the bits kept since
// the channel's first one are read backwards (the subframe under way at the start, and the
// complete words of a partly received one), and from then on each word as soon as its 30
// bits are in. Each word is checked with its own parity, using the last two bits (D29*,
// D30*) of the word before it; words 1 and 3 always follow a word whose t bits make it end in
// D29 = D30 = 0 (IS-GPS-200 20.3.5.2), so theirs are checked without the word before (in the
// polarity the preamble found), and any other word whose predecessor's last bits were not
// received is left out (its parity could not be checked).
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "receiver/navdata/ephemeris_words.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "receiver/tracking/tracking_types.hpp"
#include "signals/lnav_message.hpp"

namespace deepnav {

class NavDecoder {
 public:
  /// reference_week resolves the 10-bit week number (any week within 512 of the truth).
  NavDecoder(int prn, int reference_week);

  /// Feeds an epoch; `bit_edge_period` is the channel's bit alignment (code period at which
  /// bits start, modulo 20). Integrations of 1 to 20 ms are summed into whole bits.
  /// Returns true when a new ephemeris was completed.
  bool add(const CorrelatorEpoch& epoch, std::int64_t bit_edge_period);
  /// Feeds one data bit as the channel delivers it (TrackingChannel::take_bits()); the
  /// alternative to add(). Returns true when a new ephemeris was completed.
  bool add_bit(const PromptBit& bit);

  /// Takes the channel's time from an outside prediction before any subframe is decoded
  /// (a start guided by a navigation filter): code period `period` starts at transmit time
  /// `transmit_sow`, a whole millisecond. The first subframe decoded confirms it; one that
  /// disagrees replaces it once a second agrees (as for any anchor, see try_decode).
  void seed_time(std::int64_t period, double transmit_sow);
  /// Whether the channel's time is known: decoded, or seeded and not contradicted yet.
  bool synchronised() const { return anchor_.has_value(); }
  /// The time was seeded and no subframe has confirmed it yet.
  bool seeded() const { return seeded_; }
  const std::optional<Ephemeris>& ephemeris() const { return words_.ephemeris(); }
  const IonoParameters& iono() const { return assembler_.iono(); }
  const UtcParameters& utc() const { return assembler_.utc(); }
  /// Satellite transmit time (seconds of week) of the code period `period` plus
  /// `code_phase_chips` into it; nullopt before the first subframe.
  std::optional<double> transmit_time_sow(std::int64_t period, double code_phase_chips) const;
  /// HOW TOW (seconds of week) at the start of the last subframe decoded and the code period
  /// at which that subframe's first bit starts.
  std::optional<std::pair<double, std::int64_t>> last_subframe_start() const;
  /// The week number of the last subframe 1 decoded: its 10 bits as broadcast (WN, the
  /// week the subframe was sent in, modulo 1024) and the seconds of week at that subframe's
  /// start. nullopt before a subframe 1.
  struct WeekNumber {
    int wn10 = 0;
    double subframe_start_sow = 0.0;
  };
  const std::optional<WeekNumber>& week_number() const { return week_number_; }
  int subframes_decoded() const { return subframes_; }
  /// The last subframe decoded (every word's parity checked), with its source data words:
  /// what a NavBitPredictor learns from. Replaced at each decode; subframes_decoded() tells
  /// a caller polling after each bit that a new one arrived (at most one per bit).
  const std::optional<lnav::DecodedSubframe>& last_decoded() const { return last_decoded_; }
  /// Bit polarity found by the preamble: +1 upright, -1 inverted (Costas ambiguity); 0 unknown.
  int polarity() const { return polarity_; }
  int parity_failures() const { return failures_; }
  /// Subframes that passed parity but whose TOW count disagreed with the time the channel
  /// had (not taken; see try_decode).
  int inconsistent_subframes() const { return inconsistent_; }

 private:
  void try_decode();
  /// Every word that ends among the kept bits after the last one read (all of them, back to
  /// the channel's first bit, the first time): checked and given to the ephemeris words.
  /// Returns true when that completed or changed the ephemeris.
  bool decode_words();
  /// The word ending at kept bit `last` (its index in kept_), d1..d24 when its parity holds.
  std::optional<std::uint32_t> checked_word(std::size_t last, int word_index) const;
  struct Anchor;
  /// Whether a subframe starting at `a` agrees with the anchor (or, failing that, with the
  /// inconsistent one before it, which two agreeing subframes then replace the anchor by).
  bool consistent_with_anchor(const Anchor& a) const;

  struct Anchor {
    std::int64_t period;  ///< code period at which the subframe's first bit starts
    int tow_count;        ///< HOW TOW count (start of the next subframe, 6 s units)
  };

  int prn_;
  lnav::EphemerisAssembler assembler_;
  std::complex<double> bit_sum_{};
  int bit_ms_ = 0;
  std::deque<std::uint8_t> bits_;
  std::deque<std::int64_t> bit_start_period_;
  /// The last bits received, 0/1 as received, with the code period each starts at: a frame
  /// and a subframe, so that the first subframe decoded can be read back to the start.
  struct KeptBit {
    std::uint8_t bit;
    std::int64_t code_period;
  };
  std::deque<KeptBit> kept_;
  std::optional<std::int64_t> words_read_through_;  ///< code period of the last kept bit read into words
  EphemerisWords words_;
  std::optional<Anchor> anchor_;
  std::optional<Anchor> pending_anchor_;  ///< the last inconsistent subframe's
  std::optional<lnav::DecodedSubframe> last_decoded_;
  std::optional<WeekNumber> week_number_;
  int subframes_ = 0;
  int failures_ = 0;
  int inconsistent_ = 0;
  int polarity_ = 0;
  bool seeded_ = false;
};

/// Satellite transmit time (seconds of week) of the signal the channel's prompt replica is
/// aligned with at an absolute sample index (inside or just after the last block the channel
/// processed): what a pseudorange needs. nullopt before the first subframe is decoded.
std::optional<double> transmit_time_sow(const NavDecoder& nav, const TrackingChannel& channel,
                                        std::int64_t sample_index);

}  // namespace deepnav
