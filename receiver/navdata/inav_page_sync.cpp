#include "receiver/navdata/inav_page_sync.hpp"

#include "signals/galileo/inav_page.hpp"

namespace deepnav {
namespace {

using galileo::inav::kPagePartTotalSymbols;
using galileo::inav::kSyncPattern;
using galileo::inav::kSyncSymbols;
constexpr int kMaxMissedInRow = 3;
constexpr int kToleratedWhenLocked = 1;  // symbol errors in a pattern where one is expected
constexpr auto kPart = static_cast<std::size_t>(kPagePartTotalSymbols);

}  // namespace

int InavPageSynchronizer::pattern_at(std::size_t index, int tolerated) const {
  int differences = 0;  // from the upright pattern; the inverted one differs in the others
  for (std::size_t k = 0; k < static_cast<std::size_t>(kSyncSymbols); ++k) {
    const bool zero = buffer_[index + k].soft > 0.0;  // logic 0 is a positive level
    if (zero != (kSyncPattern[k] == 0)) ++differences;
  }
  return differences <= tolerated ? 1 : kSyncSymbols - differences <= tolerated ? -1 : 0;
}

void InavPageSynchronizer::unlock() {
  locked_ = false;
  missed_in_row_ = 0;
}

void InavPageSynchronizer::add(const E1bSymbol& symbol, std::vector<InavPagePart>& out) {
  if (!buffer_.empty() && symbol.code_period != buffer_.back().code_period + 1) {
    buffer_.clear();
    unlock();
  }
  buffer_.push_back(symbol);
  if (!locked_) {
    // Search: a pattern at the front confirmed by the same polarity one part later.
    if (buffer_.size() < kPart + kSyncSymbols) return;
    const int first = pattern_at(0, 0);
    if (first != 0 && pattern_at(kPart, 0) == first) {
      locked_ = true;
      polarity_ = first;
      missed_in_row_ = 0;
    } else {
      buffer_.pop_front();
      return;
    }
  }
  if (buffer_.size() < kPart) return;
  const int seen = pattern_at(0, kToleratedWhenLocked);
  if (seen == 0) {
    ++missed_total_;
    if (++missed_in_row_ >= kMaxMissedInRow) {
      unlock();
      buffer_.pop_front();
      return;
    }
  } else {
    missed_in_row_ = 0;
    polarity_ = seen;
  }
  InavPagePart part;
  part.first_sample = buffer_.front().first_sample;
  part.code_period = buffer_.front().code_period;
  part.polarity = polarity_;
  for (int k = 0; k < galileo::inav::kPagePartSymbols; ++k)
    part.symbols[static_cast<std::size_t>(k)] =
        static_cast<float>(polarity_ * buffer_[static_cast<std::size_t>(kSyncSymbols + k)].soft);
  out.push_back(part);
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(kPart));
}

}  // namespace deepnav
