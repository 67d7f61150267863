#include "receiver/navdata/nav_bit_monitor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "signals/lnav_parity.hpp"

namespace deepnav {

NavBitMonitor::NavBitMonitor(Config config) : config_(config) {
  if (!(config_.alarm_threshold > 0.0) || !(config_.wrong_disagreement > config_.max_error_rate) ||
      !(config_.wrong_disagreement <= 0.5) || !(config_.min_error_rate > 0.0) ||
      !(config_.max_error_rate >= config_.min_error_rate) || config_.word_confirmations < 1) {
    throw std::invalid_argument(
        fmt::format("navigation-bit monitor: expected alarm_threshold > 0, 0 < min_error_rate <= max_error_rate < "
                    "wrong_disagreement <= 0.5 and word_confirmations >= 1 (got {}, {}, {}, {}, {})",
                    config_.alarm_threshold, config_.min_error_rate, config_.max_error_rate, config_.wrong_disagreement,
                    config_.word_confirmations));
  }
}

void NavBitMonitor::reset() {
  cusum_.fill(0.0);
  for (auto& words : candidates_) words.fill(Candidate{});
  recent_ = 0;
  recent_count_ = 0;
  last_bit_ = std::numeric_limits<std::int64_t>::min();
}

void NavBitMonitor::clear_segment(int segment) {
  cusum_[static_cast<std::size_t>(segment)] = 0.0;
  candidates_[static_cast<std::size_t>(segment)].fill(Candidate{});
}

NavBitMonitor::Check NavBitMonitor::observe(NavBitPredictor& predictor, std::int64_t bit, int sign,
                                            double bit_error_rate) {
  Check check;
  check.segment = NavBitPredictor::segment_of_bit(bit);
  if (sign == 0) {  // not observed: the word being assembled is broken
    recent_count_ = 0;
    return check;
  }
  if (bit != last_bit_ + 1) recent_count_ = 0;
  last_bit_ = bit;
  recent_ = (recent_ << 1) | (sign < 0 ? 1u : 0u);
  recent_count_ = std::min(recent_count_ + 1, 64);

  check.predicted = predictor.sign(bit);
  if (check.predicted != 0) {
    const double p = std::clamp(bit_error_rate, config_.min_error_rate, config_.max_error_rate);
    const double q = config_.wrong_disagreement;
    check.disagreed = (sign < 0) != (check.predicted < 0);
    ++tested_;
    if (check.disagreed) ++disagreements_;
    double& s = cusum_[static_cast<std::size_t>(check.segment)];
    s = std::max(0.0, s + (check.disagreed ? std::log(q / p) : std::log((1.0 - q) / (1.0 - p))));
    if (s > config_.alarm_threshold) {
      check.alarm = true;
      ++alarms_;
      predictor.forget_after_failure(check.segment);
      if (NavBitPredictor::is_ephemeris_segment(check.segment)) {
        for (int e = 1; e <= 3; ++e) clear_segment(e);
      } else {
        clear_segment(check.segment);
      }
    }
  }

  const std::int64_t b = ((bit % lnav::kBitsPerWeek) + lnav::kBitsPerWeek) % lnav::kBitsPerWeek;
  if (b % lnav::kBitsPerWord == lnav::kBitsPerWord - 1)
    check.word_learned = try_learn_word(predictor, b, bit_error_rate);
  return check;
}

bool NavBitMonitor::try_learn_word(NavBitPredictor& predictor, std::int64_t b, double bit_error_rate) {
  const std::int64_t k = b / lnav::kBitsPerSubframe;
  const int word = static_cast<int>(b % lnav::kBitsPerSubframe) / lnav::kBitsPerWord;
  if (predictor.word_data_known(k, word)) return false;
  // Words 1 and 3 follow words that end in D29 = D30 = 0 by construction; the others need
  // the received D29*, D30*.
  const bool after_fixed_word = word == 0 || word == 2;
  if (recent_count_ < (after_fixed_word ? lnav::kBitsPerWord : lnav::kBitsPerWord + 2)) return false;
  const auto word30 = static_cast<std::uint32_t>(recent_ & lnav::kWordMask);
  const bool d29 = !after_fixed_word && ((recent_ >> 31) & 1u);
  const bool d30 = !after_fixed_word && ((recent_ >> 30) & 1u);
  const auto data = lnav::check_word(word30, d29, d30);
  if (!data) return false;
  if (word != 1) {  // a HOW is checked against the TOW count due there instead
    const int segment = word == 0 ? NavBitPredictor::kHeaderSegment : NavBitPredictor::segment_of_bit(b);
    Candidate& c = candidates_[static_cast<std::size_t>(segment)][static_cast<std::size_t>(word)];
    if (c.count > 0 && c.data == *data) {
      ++c.count;
    } else {
      c = Candidate{*data, 1};
    }
    const int needed = bit_error_rate <= config_.single_copy_error_rate ? 1 : config_.word_confirmations;
    if (c.count < needed) return false;
    c = Candidate{};
  }
  if (!predictor.learn_word(k, word, *data, d29, d30)) return false;
  ++words_learned_;
  return true;
}

}  // namespace deepnav
