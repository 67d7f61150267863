#pragma once
// Checks a NavBitPredictor against the signal, bit by bit, and keeps it learning.
//
// Failed-prediction detection: each 20 ms bit's prompt sign is compared with the predicted
// sign. With a correct prediction the two disagree with the bit error rate p the caller gives
// (nav_bit_error_rate(C/N0) for an ideal loop); with a wrong one (new upload, a page that
// changed, a wrong assisted word) they disagree with probability q = 0.5 (data unrelated to
// the prediction). Per knowledge segment (header, each ephemeris subframe, each page) a
// CUSUM (Page's test) accumulates the log-likelihood ratio of the two,
//   S <- max(0, S + (disagree ? ln(q / p) : ln((1 - q) / (1 - p)))),
// and declares the prediction failed when S exceeds the threshold h: the predictor forgets
// what the failure invalidates (NavBitPredictor::forget_after_failure), and the channel falls
// back to bit-edge-limited integration over those bits. At p = 1e-2 a disagreement adds 3.9
// and an agreement takes 0.68 off, so with h = 12 four disagreements in a row (a complemented
// word after a changed D30) raise the alarm, and unrelated data does after 8 bits on average
// (15 at p = 5e-2, 30 at 0.13 = 15 dB-Hz, 87 at 0.26 = 10 dB-Hz: the delay grows as h over the
// Kullback-Leibler distance between the two disagreement rates). A correct prediction raises
// a false alarm about once in 10^6 bits (5.5 h at 50 bit/s) at any of these p, when p is the
// true error rate; one that is understated makes false alarms more frequent.
//
// Learning from the signal: where the predictor does not know a word's data, the received
// word (30 bits, with the previous word's D29*, D30*; 0 for words 1 and 3) is parity-checked
// and learned (NavBitPredictor::learn_word) - at once where the bit error rate is low, after
// `word_confirmations` agreeing checked copies where it is not.
// At p = 1e-2 a word passes parity in 72 % of its repetitions, so a forgotten ephemeris is
// re-learned within a few frames even where whole-subframe decoding (5 % of subframes) fails.
//
// The sign passed to observe() is the data-bit sign as transmitted: the prompt sum's sign
// times the channel's polarity (NavDecoder::polarity()). A half-cycle slip inverts every
// comparison and shows as failures of every segment.
#include <array>
#include <cstdint>
#include <limits>

#include "receiver/navdata/nav_bit_predictor.hpp"

namespace deepnav {

class NavBitMonitor {
 public:
  struct Config {
    double alarm_threshold = 12.0;    ///< CUSUM threshold h (nats)
    double wrong_disagreement = 0.5;  ///< q: disagreement rate of a wrong prediction
    /// Parity-checked copies that must agree before a word is learned where the bit error
    /// rate exceeds single_copy_error_rate; at or below it one copy is enough. A word with 4 or
    /// more bit errors passes parity about once in 64: at p = 1e-2 a copy is wrong with
    /// probability 5e-6, at p = 0.1 with 6e-3.
    int word_confirmations = 2;
    double single_copy_error_rate = 1e-2;
    double min_error_rate = 1e-4;  ///< p is clamped into [min, max]
    double max_error_rate = 0.4;
  };

  /// What one observed bit did.
  struct Check {
    int predicted = 0;          ///< the sign predicted for the bit before it was seen (0: unknown, not tested)
    bool disagreed = false;     ///< predicted and observed signs differ
    bool alarm = false;         ///< the bit made the test declare its segment's prediction failed
    int segment = 0;            ///< the bit's knowledge segment (NavBitPredictor)
    bool word_learned = false;  ///< the bit completed a word that the predictor learned
  };

  NavBitMonitor() : NavBitMonitor(Config{}) {}
  explicit NavBitMonitor(Config config);

  /// One data bit: absolute bit index, its sign as transmitted (+1 bit 0, -1 bit 1; 0: not
  /// observed), and the probability that this sign is wrong. Bits are expected in order; a
  /// gap only restarts the word assembly.
  Check observe(NavBitPredictor& predictor, std::int64_t bit, int sign, double bit_error_rate);

  /// Forgets the received bits, test statistics and word candidates (e.g. after loss of lock).
  void reset();

  double statistic(int segment) const { return cusum_[static_cast<std::size_t>(segment)]; }
  std::int64_t bits_tested() const { return tested_; }
  std::int64_t disagreements() const { return disagreements_; }
  int alarms() const { return alarms_; }
  int words_learned() const { return words_learned_; }
  const Config& config() const { return config_; }

 private:
  struct Candidate {
    std::uint32_t data = 0;
    int count = 0;
  };
  void clear_segment(int segment);
  bool try_learn_word(NavBitPredictor& predictor, std::int64_t bit_of_week, double bit_error_rate);

  Config config_;
  std::array<double, NavBitPredictor::kSegments> cusum_{};
  std::array<std::array<Candidate, 10>, NavBitPredictor::kSegments> candidates_{};
  std::uint64_t recent_ = 0;  ///< last received bits, newest in bit 0 (1 = data bit 1)
  int recent_count_ = 0;
  std::int64_t last_bit_ = std::numeric_limits<std::int64_t>::min();
  std::int64_t tested_ = 0, disagreements_ = 0;
  int alarms_ = 0, words_learned_ = 0;
};

}  // namespace deepnav
