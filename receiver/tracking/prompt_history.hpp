#pragma once
// The 1 ms prompts a channel correlates before its data bits are synchronised, kept so that
// no bit is lost to pull-in and bit synchronisation: once the bit edge is known they become
// data bits, the first of them from the channel's first whole code period. A cold start then
// decodes the subframe that was under way when the channel started (NavDecoder).
//
// Before the carrier loop locks, the prompt's phase drifts, so the bits' signs come from a
// reference phase tracked backwards from the newest bit (where the loop holds the phase at 0
// or pi, as for the bits that follow) by decision feedback: each bit's sum, its sign undone,
// pulls the reference towards its own phase.
#include <complex>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "receiver/tracking/tracking_types.hpp"

namespace deepnav {

class PromptHistory {
 public:
  /// Keeps at most `max_periods` prompts (the oldest go first).
  explicit PromptHistory(std::size_t max_periods);

  /// The prompt integrated over code period `period`, which began at `first_sample`. A
  /// period that does not follow the last one starts the history over.
  void add(std::int64_t period, const std::complex<double>& prompt, std::int64_t first_sample);
  void clear() { prompts_.clear(); }
  std::size_t size() const { return prompts_.size(); }

  /// The bit in progress at the end of the history: the in-phase sum of its prompts.
  struct PartialBit {
    double soft = 0.0;
    int periods = 0;
    std::int64_t first_sample = 0;
    std::int64_t code_period = 0;
  };
  struct Bits {
    std::vector<PromptBit> whole;  ///< every bit of 20 kept prompts, oldest first
    PartialBit tail;               ///< the bit the history ends in (0 periods when it ends on an edge)
  };
  /// The kept prompts as data bits, bits starting at code periods `bit_edge_period` modulo 20.
  Bits bits(std::int64_t bit_edge_period) const;

 private:
  struct Prompt {
    std::int64_t period;
    std::complex<double> value;
    std::int64_t first_sample;
  };
  std::size_t max_periods_;
  std::deque<Prompt> prompts_;
};

}  // namespace deepnav
