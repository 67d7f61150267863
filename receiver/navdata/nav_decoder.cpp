#include "receiver/navdata/nav_decoder.hpp"

#include <algorithm>
#include <cmath>

#include "signals/lnav_parity.hpp"

#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr int kSubframeBits = lnav::kBitsPerSubframe;
constexpr std::uint8_t kPreamble[8] = {1, 0, 0, 0, 1, 0, 1, 1};
constexpr std::int64_t kPeriodsPerSubframe = 6000;  // 6 s of 1 ms code periods
constexpr std::int64_t kTowCountsPerWeek = 100800;
/// Bits kept for reading words: a frame and a subframe.
constexpr std::size_t kKeptBits = 6 * kSubframeBits;
constexpr std::int64_t kPeriodsPerBit = 20;
constexpr int kWordBits = lnav::kBitsPerWord;

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

}  // namespace

NavDecoder::NavDecoder(int prn, int reference_week)
    : prn_(prn), assembler_(prn, reference_week), words_(prn, reference_week) {}

bool NavDecoder::add(const CorrelatorEpoch& e, std::int64_t bit_edge_period) {
  const int ms = static_cast<int>(std::lround(e.integration_s * 1000.0));
  const std::int64_t start = e.code_period - ms;
  // Only integrations that lie inside one bit count; the bit is complete at its last ms.
  const auto phase = [&](std::int64_t p) { return code_periods_into_bit(p, bit_edge_period); };
  if (phase(start) + ms > 20) {  // straddles a bit edge (before alignment): drop it
    bit_sum_ = 0.0;
    bit_ms_ = 0;
    return false;
  }
  if (phase(start) == 0) {
    bit_sum_ = 0.0;
    bit_ms_ = 0;
  }
  bit_sum_ += e.prompt;
  bit_ms_ += ms;
  if (phase(e.code_period) != 0) return false;
  const bool whole = bit_ms_ == 20;
  const std::complex<double> sum = bit_sum_;
  bit_sum_ = 0.0;
  bit_ms_ = 0;
  if (!whole) return false;
  return add_bit(PromptBit{sum.real(), e.first_sample, e.code_period - 20});
}

bool NavDecoder::add_bit(const PromptBit& bit) {
  // Bit 1 is sent as -1 (IS-GPS-200 3.2.2); an inverted stream is caught at the preamble.
  const std::uint8_t value = bit.soft < 0.0 ? 1 : 0;
  bits_.push_back(value);
  bit_start_period_.push_back(bit.code_period);
  kept_.push_back(KeptBit{value, bit.code_period});
  if (kept_.size() > kKeptBits) kept_.pop_front();
  try_decode();
  return decode_words();
}

bool NavDecoder::decode_words() {
  if (!anchor_ || seeded_) return false;  // word boundaries known only from a decoded subframe
  bool changed = false;
  std::size_t unread = kept_.size();
  while (unread > 0 && !(words_read_through_ && kept_[unread - 1].code_period <= *words_read_through_)) --unread;
  for (std::size_t i = unread; i < kept_.size(); ++i) {
    const std::int64_t period = kept_[i].code_period;
    const std::int64_t from_anchor = period - anchor_->period;
    if (from_anchor % kPeriodsPerBit != 0) continue;  // not on the anchor's bit grid
    const std::int64_t bit = from_anchor / kPeriodsPerBit;
    const std::int64_t subframes = floor_div(bit, kSubframeBits);
    const auto in_subframe = static_cast<int>(bit - subframes * kSubframeBits);
    if (in_subframe % kWordBits != kWordBits - 1) continue;  // not a word's last bit
    const int word_index = in_subframe / kWordBits;
    const auto data = checked_word(i, word_index);
    if (!data) continue;
    const std::int64_t subframe_of_week =
        ((anchor_->tow_count - 1 + subframes) % kTowCountsPerWeek + kTowCountsPerWeek) % kTowCountsPerWeek;
    if (word_index == 2 && lnav::subframe_id_at(subframe_of_week) == 1 && !week_number_)
      week_number_ = WeekNumber{lnav::week_number_in_word3(*data), static_cast<double>(subframe_of_week) * 6.0};
    changed = words_.add(subframe_of_week, word_index, *data) || changed;
  }
  if (!kept_.empty()) words_read_through_ = kept_.back().code_period;
  return changed;
}

std::optional<std::uint32_t> NavDecoder::checked_word(std::size_t last, int word_index) const {
  if (last + 1 < static_cast<std::size_t>(kWordBits)) return std::nullopt;
  const std::size_t first = last + 1 - kWordBits;
  // The 30 bits, and the two before them where the parity needs them, without a gap.
  const bool structural = word_index == 0 || word_index == 2;
  const std::size_t from = structural ? first : first - std::min<std::size_t>(first, 2);
  if (!structural && first < 2) return std::nullopt;
  for (std::size_t k = from; k < last; ++k)
    if (kept_[k + 1].code_period != kept_[k].code_period + kPeriodsPerBit) return std::nullopt;
  const std::uint8_t flip = polarity_ < 0 ? 1 : 0;
  std::uint32_t word = 0;
  for (std::size_t k = first; k <= last; ++k) word = (word << 1) | static_cast<std::uint32_t>(kept_[k].bit ^ flip);
  bool d29 = false, d30 = false;
  if (!structural) {
    d29 = (kept_[first - 2].bit ^ flip) != 0;
    d30 = (kept_[first - 1].bit ^ flip) != 0;
  }
  return lnav::check_word(word, d29, d30);
}

void NavDecoder::try_decode() {
  while (bits_.size() >= static_cast<std::size_t>(kSubframeBits)) {
    // Preamble, either polarity, at the front of the buffer.
    bool normal = true, inverted = true;
    for (int i = 0; i < 8; ++i) {
      normal = normal && bits_[static_cast<std::size_t>(i)] == kPreamble[i];
      inverted = inverted && bits_[static_cast<std::size_t>(i)] != kPreamble[i];
    }
    if (normal || inverted) {
      lnav::Subframe sf{};
      for (int w = 0; w < 10; ++w) {
        std::uint32_t word = 0;
        for (int b = 0; b < 30; ++b) word = (word << 1) | bits_[static_cast<std::size_t>(w * 30 + b)];
        sf[static_cast<std::size_t>(w)] = word;
      }
      const auto decoded = lnav::decode_subframe(sf);
      if (decoded && !consistent_with_anchor(Anchor{bit_start_period_.front(), decoded->tlm_how.tow_count})) {
        // Every word passed parity, but the TOW count is not the one the channel's own code
        // period count says is due: a subframe read wrong (weak signal: several errors in a
        // word pass parity once in 64), or the anchor itself was. Neither is taken until a
        // second subframe agrees with it.
        ++inconsistent_;
        pending_anchor_ = Anchor{bit_start_period_.front(), decoded->tlm_how.tow_count};
      } else if (decoded) {
        pending_anchor_.reset();
        seeded_ = false;
        anchor_ = Anchor{bit_start_period_.front(), decoded->tlm_how.tow_count};
        if (decoded->tlm_how.subframe_id == 1)
          // A TOW count of 0 (the next subframe starts the week): this one began 6 s before.
          week_number_ =
              WeekNumber{decoded->eph.week & 0x3FF,
                         decoded->tlm_how.tow_count == 0 ? 604794.0 : (decoded->tlm_how.tow_count - 1) * 6.0};
        polarity_ = normal ? 1 : -1;
        assembler_.add(*decoded);
        last_decoded_ = *decoded;
        ++subframes_;
        bits_.erase(bits_.begin(), bits_.begin() + kSubframeBits);
        bit_start_period_.erase(bit_start_period_.begin(), bit_start_period_.begin() + kSubframeBits);
        continue;
      } else {
        ++failures_;
      }
    }
    bits_.pop_front();
    bit_start_period_.pop_front();
  }
}

void NavDecoder::seed_time(std::int64_t period, double transmit_sow) {
  if (anchor_) return;  // a decoded (or earlier) time stands
  constexpr std::int64_t kMsPerWeek = kTowCountsPerWeek * kPeriodsPerSubframe;
  const std::int64_t ms = ((std::llround(transmit_sow * 1e3) % kMsPerWeek) + kMsPerWeek) % kMsPerWeek;
  const std::int64_t into_subframe = ms % kPeriodsPerSubframe;
  // The anchor is the start of the subframe the period lies in: its TOW count names the next one.
  anchor_ = Anchor{period - into_subframe, static_cast<int>((ms / kPeriodsPerSubframe + 1) % kTowCountsPerWeek)};
  seeded_ = true;
}

bool NavDecoder::consistent_with_anchor(const Anchor& a) const {
  // TOW counts of subframes k periods apart differ by k / 6000 (modulo a week of counts).
  const auto agrees = [&](const Anchor& ref) {
    const std::int64_t periods = a.period - ref.period;
    if (periods % kPeriodsPerSubframe != 0) return false;
    const std::int64_t due = (ref.tow_count + periods / kPeriodsPerSubframe) % kTowCountsPerWeek;
    return (due + kTowCountsPerWeek) % kTowCountsPerWeek == a.tow_count;
  };
  if (!anchor_) return true;
  if (agrees(*anchor_)) return true;
  return pending_anchor_ && agrees(*pending_anchor_);  // two that agree outvote the anchor
}

std::optional<std::pair<double, std::int64_t>> NavDecoder::last_subframe_start() const {
  if (!anchor_) return std::nullopt;
  return std::make_pair((anchor_->tow_count - 1) * 6.0, anchor_->period);
}

std::optional<double> transmit_time_sow(const NavDecoder& nav, const TrackingChannel& channel,
                                        std::int64_t sample_index) {
  const double chips = channel.code_chips_at(sample_index);
  const double periods = std::floor(chips / gps::kCodeLength_chips);
  return nav.transmit_time_sow(static_cast<std::int64_t>(periods), chips - periods * gps::kCodeLength_chips);
}

std::optional<double> NavDecoder::transmit_time_sow(std::int64_t period, double code_phase_chips) const {
  if (!anchor_) return std::nullopt;
  const double subframe_start_sow = (anchor_->tow_count - 1) * 6.0;
  double t =
      subframe_start_sow + static_cast<double>(period - anchor_->period) * 1e-3 + code_phase_chips / gps::kCodeRate_cps;
  if (t < 0.0) t += 604800.0;
  return t;
}

}  // namespace deepnav
