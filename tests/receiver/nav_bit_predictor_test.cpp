#include "receiver/navdata/nav_bit_predictor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "receiver/navdata/nav_bit_monitor.hpp"
#include "receiver/navdata/nav_decoder.hpp"
#include "signals/lnav_parity.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/lnav_broadcast.hpp"

namespace deepnav {
namespace {

constexpr std::int64_t kSfBits = lnav::kBitsPerSubframe;
constexpr std::int64_t kCycleSubframes = 5 * lnav::kPagesPerCycle;  // 12.5 min

const NavData& nav_file() {
  static const NavData nav = read_rinex_nav(std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n");
  return nav;
}

const Ephemeris& ephemeris(int prn, double toe_s) {
  for (const auto& e : nav_file().ephemerides) {
    if (e.prn == prn && e.toe_s == toe_s) return e;
  }
  throw std::runtime_error("test ephemeris missing");
}

/// Absolute subframe count (from the GPS time origin) of the subframe that starts at or
/// after `sow` of `week`.
std::int64_t subframe_at(int week, double sow) {
  return std::int64_t{week} * lnav::kTowCountsPerWeek + static_cast<std::int64_t>(std::ceil(sow / 6.0));
}

/// The synthesizer's bit stream of one satellite over the subframes [first, last).
LnavSignTable stream(const Ephemeris& eph, std::int64_t first_subframe, std::int64_t last_subframe) {
  return LnavSignTable(synthesized_lnav_content(nav_file(), eph), first_subframe * 6000, last_subframe * 6000 - 1);
}

/// A subframe of the stream decoded as a receiver decodes it (from its transmitted bits).
lnav::DecodedSubframe decoded(const LnavSignTable& table, std::int64_t subframe) {
  lnav::Subframe words{};
  for (int i = 0; i < kSfBits; ++i) {
    const int bit = table.sign_of_bit(subframe * kSfBits + i) < 0 ? 1 : 0;
    words[static_cast<std::size_t>(i / 30)] =
        (words[static_cast<std::size_t>(i / 30)] << 1) | static_cast<std::uint32_t>(bit);
  }
  const auto d = lnav::decode_subframe(words);
  if (!d) throw std::runtime_error("test stream failed to decode");
  return *d;
}

int page_of(std::int64_t subframe) { return lnav::page_at(subframe % lnav::kTowCountsPerWeek); }
int id_of(std::int64_t subframe) { return lnav::subframe_id_at(subframe % lnav::kTowCountsPerWeek); }

struct Tally {
  std::int64_t known = 0, unknown = 0, wrong = 0;
};

Tally compare(const NavBitPredictor& p, const LnavSignTable& table, std::int64_t first_subframe,
              std::int64_t n_subframes) {
  Tally t;
  std::vector<std::int8_t> signs(static_cast<std::size_t>(n_subframes * kSfBits));
  p.signs(first_subframe * kSfBits, signs);
  for (std::size_t i = 0; i < signs.size(); ++i) {
    if (signs[i] == 0) {
      ++t.unknown;
    } else if (signs[i] == table.sign_of_bit(first_subframe * kSfBits + static_cast<std::int64_t>(i))) {
      ++t.known;
    } else {
      ++t.wrong;
    }
  }
  return t;
}

TEST(NavBitPredictor, PredictsAPageCycleAfterOneFrameAndExactlyAfterAllPages) {
  const Ephemeris& eph = ephemeris(10, 525600.0);
  // Start at a frame boundary in the middle of a page cycle (page != 1).
  std::int64_t s0 = subframe_at(2190, 525700.0);
  while (id_of(s0) != 1) ++s0;
  const LnavSignTable table = stream(eph, s0, s0 + 1 + 3 * kCycleSubframes);
  const int p0 = page_of(s0);
  ASSERT_NE(p0, 1);

  NavBitPredictor predictor;
  // Before anything is learned only the preambles are known.
  const Tally none = compare(predictor, table, s0, 5);
  EXPECT_EQ(none.wrong, 0);
  EXPECT_EQ(none.known, 5 * 8);

  for (std::int64_t s = s0; s < s0 + 5; ++s) predictor.learn(decoded(table, s));
  // One frame learned: the next full page cycle is predicted without a single wrong bit;
  // subframes 1-3 and every header are known, of subframes 4 and 5 only page p0's bodies.
  std::int64_t expected_known = 0;
  for (std::int64_t s = s0 + 5; s < s0 + 5 + kCycleSubframes; ++s) {
    expected_known += (id_of(s) <= 3 || page_of(s) == p0) ? kSfBits : 60;
  }
  const Tally one_frame = compare(predictor, table, s0 + 5, kCycleSubframes);
  EXPECT_EQ(one_frame.wrong, 0);
  EXPECT_EQ(one_frame.known, expected_known);
  EXPECT_EQ(one_frame.known + one_frame.unknown, kCycleSubframes * kSfBits);

  // Learning through that cycle: the following cycle is predicted exactly, every bit.
  for (std::int64_t s = s0 + 5; s < s0 + 5 + kCycleSubframes; ++s) predictor.learn(decoded(table, s));
  const Tally full = compare(predictor, table, s0 + 5 + kCycleSubframes, kCycleSubframes);
  EXPECT_EQ(full.wrong, 0);
  EXPECT_EQ(full.unknown, 0);
  EXPECT_EQ(predictor.uploads_seen(), 0);
  for (int segment = 1; segment < NavBitPredictor::kSegments; ++segment) {
    EXPECT_EQ(predictor.body_words_known(segment), 8) << segment;
    EXPECT_EQ(predictor.source(segment), NavBitPredictor::Source::broadcast);
  }
}

TEST(NavBitPredictor, TheWeekNumberRollingOverIsNoUpload) {
  // Subframe 1 in the last frame of week 2190 and the first of 2191: the same data set with
  // WN 2190 then 2191. No upload, and subframes 2 and 3 stay known.
  const Ephemeris& eph = ephemeris(10, 597600.0);
  const std::int64_t week_end = subframe_at(2191, 0.0);
  const LnavSignTable table = stream(eph, week_end - 5, week_end + 5);
  NavBitPredictor predictor;
  for (std::int64_t s = week_end - 5; s < week_end + 1; ++s) predictor.learn(decoded(table, s));
  EXPECT_EQ(predictor.uploads_seen(), 0);
  EXPECT_EQ(predictor.body_words_known(2), 8);
  EXPECT_EQ(predictor.body_words_known(3), 8);
}

TEST(NavBitPredictor, HowCountsAcrossTheFrameAndWeekBoundary) {
  const Ephemeris& eph = ephemeris(10, 597600.0);
  const std::int64_t week_end = subframe_at(2191, 0.0);  // first subframe of week 2191
  const std::int64_t learn_from = week_end - 2 * kCycleSubframes;
  const LnavSignTable table = stream(eph, learn_from, week_end + kCycleSubframes);
  NavBitPredictor predictor;
  // All 25 pages, learned before the last 12.5 min of the week.
  for (std::int64_t s = learn_from; s < learn_from + kCycleSubframes; ++s) predictor.learn(decoded(table, s));

  // The last 12.5 min of week 2190 and the first of week 2191, in absolute bits: exact.
  const Tally across = compare(predictor, table, week_end - kCycleSubframes, 2 * kCycleSubframes);
  EXPECT_EQ(across.wrong, 0);
  EXPECT_EQ(across.unknown, 0);

  // The predicted HOWs: TOW count of the next subframe (0 in the week's last subframe), the
  // subframe ID through 4, 5 | 1, 2 and the page cycle restarting at page 1 in the new week
  // after page 10 in the week's last frame.
  const auto predicted_subframe = [&](std::int64_t s) {
    lnav::Subframe words{};
    for (int i = 0; i < kSfBits; ++i) {
      const int sign = predictor.sign(s * kSfBits + i);
      EXPECT_NE(sign, 0);
      words[static_cast<std::size_t>(i / 30)] = (words[static_cast<std::size_t>(i / 30)] << 1) | (sign < 0 ? 1u : 0u);
    }
    const auto d = lnav::decode_subframe(words);
    EXPECT_TRUE(d.has_value());
    return d.value_or(lnav::DecodedSubframe{});
  };
  const std::array<int, 4> tows = {lnav::kTowCountsPerWeek - 1, 0, 1, 2};
  const std::array<int, 4> ids = {4, 5, 1, 2};
  for (int j = 0; j < 4; ++j) {
    const auto d = predicted_subframe(week_end - 2 + j);
    EXPECT_EQ(d.tlm_how.tow_count, tows[static_cast<std::size_t>(j)]) << j;
    EXPECT_EQ(d.tlm_how.subframe_id, ids[static_cast<std::size_t>(j)]) << j;
    if (j == 1) {
      EXPECT_EQ(d.page, 10);
    }
  }
  EXPECT_EQ(predicted_subframe(week_end + 3).page, 1);
  EXPECT_EQ(predicted_subframe(week_end + 8).page, 2);
  // The same bit addressed through GPS time.
  const std::int64_t b = nav_bit_index(GpsTime{2191, 0.01});
  EXPECT_EQ(b, week_end * kSfBits);
  EXPECT_EQ(predictor.sign(b), table.sign_of_bit(b));
  EXPECT_EQ(nav_bit_index(GpsTime{2190, 604799.99}), b - 1);
}

TEST(NavBitPredictor, LearnsFromTheNavDecoder) {
  const Ephemeris& eph = ephemeris(10, 525600.0);
  const std::int64_t s0 = subframe_at(2190, 525600.0);
  const LnavSignTable table = stream(eph, s0, s0 + 20);
  NavDecoder decoder(10, 2190);
  NavBitPredictor predictor;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  int seen = 0;
  // Mid-subframe start, inverted polarity, 6 dB per-bit SNR with noise.
  for (std::int64_t b = s0 * kSfBits + 137; b < (s0 + 12) * kSfBits; ++b) {
    const double soft = -4.0 * table.sign_of_bit(b) + noise(rng);
    decoder.add_bit(PromptBit{soft, 0, 20 * b});
    if (decoder.subframes_decoded() != seen) {
      seen = decoder.subframes_decoded();
      predictor.learn(*decoder.last_decoded());
    }
  }
  EXPECT_EQ(decoder.polarity(), -1);
  ASSERT_GE(seen, 10);
  // Subframes 3, 4, 5, 1, 2: all known but the bodies of the pages not decoded yet.
  const Tally t = compare(predictor, table, s0 + 12, 5);
  EXPECT_EQ(t.wrong, 0);
  EXPECT_EQ(t.unknown, 2 * (kSfBits - 60));
}

TEST(NavBitPredictor, AWordIsPredictedWithTheChainItWasReceivedWith) {
  const Ephemeris& eph = ephemeris(10, 525600.0);
  std::int64_t s1 = subframe_at(2190, 526000.0);
  while (id_of(s1) != 2) ++s1;
  const LnavSignTable table = stream(eph, s1, s1 + 10);
  const lnav::DecodedSubframe sf = decoded(table, s1);
  const lnav::Subframe words = lnav::encode_words(sf.data);
  NavBitPredictor predictor;
  // Word 6 alone (its previous word unknown), with the D29*, D30* of word 5 as received.
  ASSERT_TRUE(predictor.learn_word(s1, 5, sf.data[5], lnav::word_d29(words[4]), lnav::word_d30(words[4])));
  EXPECT_EQ(predictor.body_words_known(2), 1);
  for (const std::int64_t s : {s1, s1 + 5}) {  // this subframe 2 and the next frame's
    for (int i = 8; i < kSfBits; ++i) {
      const std::int64_t b = s * kSfBits + i;
      EXPECT_EQ(predictor.sign(b), i / 30 == 5 ? table.sign_of_bit(b) : 0) << i;
    }
  }
  // A HOW is taken only with the TOW count due at that subframe.
  EXPECT_FALSE(predictor.learn_word(s1 + 1, 1, sf.data[1]));
  EXPECT_EQ(predictor.how_mismatches(), 1);
  EXPECT_TRUE(predictor.learn_word(s1, 1, sf.data[1]));
  EXPECT_FALSE(predictor.learn_word(s1, 0, sf.data[0] ^ 0x800000u));  // no preamble
  EXPECT_FALSE(predictor.tlm_known());
  EXPECT_TRUE(predictor.learn_word(s1, 0, sf.data[0]));
  const std::int64_t b = (s1 + 5) * kSfBits + 45;  // in the next subframe 2's HOW
  EXPECT_EQ(predictor.sign(b), table.sign_of_bit(b));
  // Addressed by GPS time: the middle of that bit.
  const double t = static_cast<double>(b % lnav::kBitsPerWeek) * 0.02 + 0.01;
  EXPECT_EQ(predictor.sign_at(GpsTime{static_cast<int>(b / lnav::kBitsPerWeek), t}), table.sign_of_bit(b));
}

/// Feeds the stream's bits [first, last) with independent sign errors of probability p to
/// the monitor; returns the bit of each alarm.
std::vector<std::int64_t> observe(NavBitMonitor& monitor, NavBitPredictor& predictor,
                                  const std::function<int(std::int64_t)>& truth, std::int64_t first, std::int64_t last,
                                  double p, std::mt19937_64& rng) {
  std::bernoulli_distribution flip(p);
  std::vector<std::int64_t> alarms;
  for (std::int64_t b = first; b < last; ++b) {
    const int sign = flip(rng) ? -truth(b) : truth(b);
    if (monitor.observe(predictor, b, sign, p).alarm) alarms.push_back(b);
  }
  return alarms;
}

TEST(NavBitMonitor, CorrectPredictionsRaiseNoAlarm) {
  const Ephemeris& eph = ephemeris(10, 525600.0);
  const std::int64_t s0 = subframe_at(2190, 540000.0);
  const LnavSignTable table = stream(eph, s0, s0 + 2 * kCycleSubframes);
  NavBitPredictor predictor;
  for (std::int64_t s = s0; s < s0 + kCycleSubframes; ++s) predictor.learn(decoded(table, s));
  for (const double p : {1e-2, 0.1}) {
    NavBitPredictor copy = predictor;
    NavBitMonitor monitor;
    std::mt19937_64 rng(11);
    const auto alarms = observe(
        monitor, copy, [&](std::int64_t b) { return table.sign_of_bit(b); }, (s0 + kCycleSubframes) * kSfBits,
        (s0 + 2 * kCycleSubframes) * kSfBits, p, rng);
    EXPECT_TRUE(alarms.empty()) << p;
    EXPECT_EQ(monitor.bits_tested(), kCycleSubframes * kSfBits);
    EXPECT_NEAR(static_cast<double>(monitor.disagreements()) / static_cast<double>(monitor.bits_tested()), p, 0.2 * p);
  }
}

TEST(NavBitMonitor, NewUploadDetectedWithinAFewBitsAndRelearned) {
  const Ephemeris& old_eph = ephemeris(10, 525600.0);  // IODE 71
  const Ephemeris& new_eph = ephemeris(10, 532800.0);  // IODE 75, uploaded from 529230 s
  std::int64_t cutover = subframe_at(2190, 529230.0);
  while (id_of(cutover) != 1) ++cutover;
  const std::int64_t first = cutover - 3 * kCycleSubframes;
  const std::int64_t last = cutover + 60;  // 12 frames after the upload
  const LnavSignTable before = stream(old_eph, first, last);
  const LnavSignTable after = stream(new_eph, first, last);
  const auto truth = [&](std::int64_t b) {
    return b < cutover * kSfBits ? before.sign_of_bit(b) : after.sign_of_bit(b);
  };

  NavBitPredictor learned;
  for (std::int64_t s = first; s < first + 5; ++s) learned.learn(decoded(before, s));
  // The first bit the old data set predicts wrongly.
  std::int64_t first_wrong = cutover * kSfBits;
  while (learned.sign(first_wrong) == 0 || learned.sign(first_wrong) == truth(first_wrong)) ++first_wrong;
  EXPECT_LT(first_wrong, (cutover + 1) * kSfBits);  // in the new subframe 1

  const double p = 1e-2;
  std::int64_t worst_delay = 0, worst_wrong_used = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    NavBitPredictor predictor = learned;
    NavBitMonitor monitor;
    std::mt19937_64 rng(seed);
    const auto quiet = observe(monitor, predictor, truth, (first + 5) * kSfBits, cutover * kSfBits, p, rng);
    EXPECT_TRUE(quiet.empty()) << seed;
    const auto alarms = observe(monitor, predictor, truth, cutover * kSfBits, last * kSfBits, p, rng);
    ASSERT_EQ(alarms.size(), 1u) << seed;
    const std::int64_t delay = alarms[0] - first_wrong;
    std::int64_t wrong_used = 0;
    for (std::int64_t b = first_wrong; b <= alarms[0]; ++b)
      wrong_used += learned.sign(b) != 0 && learned.sign(b) != truth(b) ? 1 : 0;
    EXPECT_GE(delay, 0) << seed;
    worst_delay = std::max(worst_delay, delay);
    worst_wrong_used = std::max(worst_wrong_used, wrong_used);
    // Re-learned from the signal word by word: the last frame is predicted exactly.
    const Tally t = compare(predictor, after, last - 5, 5);
    EXPECT_EQ(t.wrong, 0) << seed;
    for (int segment = 1; segment <= 3; ++segment) EXPECT_EQ(predictor.body_words_known(segment), 8) << seed;
  }
  std::printf(
      "upload at p = %.0e: alarm at most %lld bits after the first wrong prediction, "
      "at most %lld wrongly predicted bits used\n",
      p, static_cast<long long>(worst_delay), static_cast<long long>(worst_wrong_used));
  EXPECT_LE(worst_delay, 40);
  EXPECT_LE(worst_wrong_used, 8);
}

TEST(NavBitPredictor, DecodedUploadReplacesTheDataSet) {
  const std::int64_t s0 = subframe_at(2190, 529230.0);
  const LnavSignTable before = stream(ephemeris(10, 525600.0), s0, s0 + 20);
  const LnavSignTable after = stream(ephemeris(10, 532800.0), s0, s0 + 20);
  NavBitPredictor predictor;
  for (std::int64_t s = s0; s < s0 + 5; ++s) predictor.learn(decoded(before, s));
  std::int64_t s1 = s0 + 5;
  while (id_of(s1) != 1) ++s1;
  predictor.learn(decoded(after, s1));
  EXPECT_EQ(predictor.uploads_seen(), 1);
  EXPECT_EQ(predictor.body_words_known(1), 8);
  EXPECT_EQ(predictor.body_words_known(2), 0);  // old data set: forgotten
  EXPECT_EQ(predictor.body_words_known(3), 0);
  predictor.learn(decoded(after, s1 + 1));
  predictor.learn(decoded(after, s1 + 2));
  EXPECT_EQ(predictor.uploads_seen(), 1);
  const Tally t = compare(predictor, after, s1 + 5, 3);
  EXPECT_EQ(t.wrong, 0);
  EXPECT_EQ(t.unknown, 0);
}

TEST(NavBitPredictor, AssistedSubframesFromTheNavigationFile) {
  const Ephemeris& eph = ephemeris(12, 525600.0);
  std::int64_t s0 = subframe_at(2190, 526000.0);
  while (id_of(s0) != 1) ++s0;
  const LnavSignTable table = stream(eph, s0, s0 + 5 * 30);
  NavBitPredictor predictor;
  predictor.assist(eph, lnav::TlmHow{});
  EXPECT_EQ(predictor.source(1), NavBitPredictor::Source::assisted);
  // Subframes 1-3 and the headers exactly; the pages unknown.
  const Tally t = compare(predictor, table, s0, 5);
  EXPECT_EQ(t.wrong, 0);
  EXPECT_EQ(t.known, 3 * kSfBits + 2 * 60);

  // Assisted with an older data set: the broadcast disagrees in subframe 1, the monitor
  // detects it, and the set is learned from the signal.
  NavBitPredictor stale;
  stale.assist(ephemeris(12, 518400.0));
  EXPECT_FALSE(stale.tlm_known());
  NavBitMonitor monitor;
  std::mt19937_64 rng(5);
  const auto alarms = observe(
      monitor, stale, [&](std::int64_t b) { return table.sign_of_bit(b); }, s0 * kSfBits, (s0 + 5 * 30) * kSfBits, 1e-2,
      rng);
  ASSERT_GE(alarms.size(), 1u);
  EXPECT_LT(alarms[0], (s0 + 1) * kSfBits);  // in the first subframe 1
  EXPECT_TRUE(stale.tlm_known());
  EXPECT_TRUE(stale.how_known());
  const Tally relearned = compare(stale, table, s0 + 5 * 29, 5);
  EXPECT_EQ(relearned.wrong, 0);
  for (int segment = 1; segment <= 3; ++segment) {
    EXPECT_EQ(stale.body_words_known(segment), 8);
    EXPECT_EQ(stale.source(segment), NavBitPredictor::Source::broadcast);
  }
}

TEST(NavBitMonitor, LearnsEveryPageFromAWeakStream) {
  const Ephemeris& eph = ephemeris(10, 525600.0);
  const std::int64_t s0 = subframe_at(2190, 550000.0);
  const LnavSignTable table = stream(eph, s0, s0 + 4 * kCycleSubframes);
  // From nothing, at bit error rates where whole subframes rarely decode (5 % at 1e-2, 2e-7
  // at 5e-2): parity-checked words, one copy at 1e-2, two agreeing copies at 5e-2.
  for (const double p : {1e-2, 5e-2}) {
    NavBitPredictor predictor;
    NavBitMonitor monitor;
    std::mt19937_64 rng(17);
    const auto alarms = observe(
        monitor, predictor, [&](std::int64_t b) { return table.sign_of_bit(b); }, s0 * kSfBits,
        (s0 + 3 * kCycleSubframes) * kSfBits, p, rng);
    EXPECT_TRUE(alarms.empty()) << p;
    const Tally t = compare(predictor, table, s0 + 3 * kCycleSubframes, kCycleSubframes);
    EXPECT_EQ(t.wrong, 0) << p;
    const double fraction = static_cast<double>(t.known) / static_cast<double>(t.known + t.unknown);
    std::printf("after 3 page cycles at p = %.0e: %.4f of the next cycle's bits predicted, %d words learned\n", p,
                fraction, monitor.words_learned());
    for (int segment = 1; segment <= 3; ++segment) EXPECT_EQ(predictor.body_words_known(segment), 8) << p;
    EXPECT_GT(fraction, p < 0.02 ? 0.98 : 0.5) << p;
  }
}

TEST(NavBitPredictor, BitErrorRateAndSegments) {
  EXPECT_NEAR(nav_bit_error_rate(20.0), 0.02275, 1e-4);  // Q(2)
  EXPECT_NEAR(nav_bit_error_rate(10.0), 0.2635, 1e-3);
  EXPECT_LT(nav_bit_error_rate(30.0), 1e-9);
  EXPECT_EQ(NavBitPredictor::body_segment(1, 0), 1);
  EXPECT_EQ(NavBitPredictor::body_segment(4, 1), 4);
  EXPECT_EQ(NavBitPredictor::body_segment(5, 25), 53);
  EXPECT_THROW(NavBitPredictor::body_segment(4, 26), std::invalid_argument);
  EXPECT_EQ(NavBitPredictor::segment_of_bit(59), NavBitPredictor::kHeaderSegment);
  EXPECT_EQ(NavBitPredictor::segment_of_bit(60), 1);
  EXPECT_EQ(NavBitPredictor::segment_of_bit(4 * kSfBits + 60), NavBitPredictor::body_segment(5, 1));
  EXPECT_THROW(NavBitMonitor(NavBitMonitor::Config{.alarm_threshold = 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
