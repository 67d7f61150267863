#pragma once
// A spreading code as the correlator kernels read it: one level (+-1) per table entry, as
// int16 and int8, padded with the wrapped-around entries before 0 and after the end so that
// the SIMD kernels' window loads and the tap offsets never need a modulo. An entry is a C/A
// chip or, for the E1 BOC(1,1) replica, a half-chip (the subcarrier's sign folded in).
// Internal to the correlators (receiver/tracking/correlator.hpp, e1_correlator.hpp).
#include <array>
#include <cstdint>
#include <memory>

#include "receiver/tracking/kernels/kernels.hpp"

namespace deepnav::correlator_detail {

/// The kernels' view of a table: pointers at entry 0 (valid from -kPad to period - 1 + kPad).
struct PaddedCode {
  const std::int16_t* l16 = nullptr;
  const std::int8_t* l8 = nullptr;
  int period = 0;
};

template <int kPeriod>
struct PaddedCodeTable {
  alignas(64) std::int16_t l16[kPeriod + 2 * kPad];
  alignas(64) std::int8_t l8[kPeriod + 2 * kPad];
  /// level(e) gives entry e in [0, kPeriod).
  template <class Level>
  explicit PaddedCodeTable(Level level) {
    for (int e = -kPad; e < kPeriod + kPad; ++e) {
      const auto v = static_cast<std::int8_t>(level((e + kPeriod) % kPeriod));
      l16[e + kPad] = v;
      l8[e + kPad] = v;
    }
  }
  PaddedCode view() const { return {l16 + kPad, l8 + kPad, kPeriod}; }
};

/// This thread's table of a code, for the last `kEntries` codes it saw, keyed by address and
/// checked against a copy of the chips (a caller may reuse an address for another code).
template <class Chips, class Table, class Make>
const Table& cached_code_table(const Chips& code, Make make) {
  struct Entry {
    const Chips* key = nullptr;
    Chips chips{};
    std::unique_ptr<Table> table;
  };
  constexpr int kEntries = 64;
  thread_local std::array<Entry, kEntries> cache;
  thread_local int next = 0;
  for (Entry& e : cache) {
    if (e.key == &code) {
      if (e.chips != code) {
        e.chips = code;
        e.table = make(code);
      }
      return *e.table;
    }
  }
  Entry& e = cache[static_cast<std::size_t>(next)];
  next = (next + 1) % kEntries;
  e.key = &code;
  e.chips = code;
  e.table = make(code);
  return *e.table;
}

}  // namespace deepnav::correlator_detail
