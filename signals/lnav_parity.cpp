#include "signals/lnav_parity.hpp"

#include <bit>
#include <initializer_list>

namespace deepnav::lnav {
namespace {

// Mask over d1..d24 (d1 at bit 23) of the source bits summed by one parity equation.
constexpr std::uint32_t mask_of(std::initializer_list<int> d_indices) {
  std::uint32_t mask = 0;
  for (int i : d_indices) mask |= 1u << (24 - i);
  return mask;
}

struct ParityEquation {
  std::uint32_t mask;
  bool uses_d29;  ///< true: the equation adds D29*, false: it adds D30*
};

// Table 20-XIV, D25 .. D30 in order.
constexpr ParityEquation kEquations[6] = {
    {mask_of({1, 2, 3, 5, 6, 10, 11, 12, 13, 14, 17, 18, 20, 23}), true},
    {mask_of({2, 3, 4, 6, 7, 11, 12, 13, 14, 15, 18, 19, 21, 24}), false},
    {mask_of({1, 3, 4, 5, 7, 8, 12, 13, 14, 15, 16, 19, 20, 22}), true},
    {mask_of({2, 4, 5, 6, 8, 9, 13, 14, 15, 16, 17, 20, 21, 23}), false},
    {mask_of({1, 3, 5, 6, 7, 9, 10, 14, 15, 16, 17, 18, 21, 22, 24}), false},
    {mask_of({3, 5, 6, 8, 9, 10, 11, 13, 15, 19, 22, 23, 24}), true},
};

}  // namespace

std::uint32_t parity_bits(std::uint32_t data24, bool prev_d29, bool prev_d30) {
  data24 &= kDataMask;
  std::uint32_t parity = 0;
  for (const auto& eq : kEquations) {
    const bool prev = eq.uses_d29 ? prev_d29 : prev_d30;
    const auto bit = static_cast<std::uint32_t>(std::popcount(data24 & eq.mask) & 1) ^ (prev ? 1u : 0u);
    parity = (parity << 1) | bit;
  }
  return parity;
}

std::uint32_t encode_word(std::uint32_t data24, bool prev_d29, bool prev_d30) {
  data24 &= kDataMask;
  const std::uint32_t sent = prev_d30 ? (~data24 & kDataMask) : data24;
  return (sent << 6) | parity_bits(data24, prev_d29, prev_d30);
}

std::optional<std::uint32_t> check_word(std::uint32_t word30, bool prev_d29, bool prev_d30) {
  word30 &= kWordMask;
  const std::uint32_t sent = word30 >> 6;
  const std::uint32_t data24 = prev_d30 ? (~sent & kDataMask) : sent;
  if (parity_bits(data24, prev_d29, prev_d30) != (word30 & 0x3Fu)) return std::nullopt;
  return data24;
}

std::uint32_t with_noninformation_bits(std::uint32_t data24, bool prev_d29, bool prev_d30) {
  // D29 involves d24 but not d23, D30 involves both: fix d24 from D29 first, then d23 from D30.
  std::uint32_t d = data24 & kDataMask & ~0x3u;
  if (parity_bits(d, prev_d29, prev_d30) & 0x2u) d |= 0x1u;
  if (parity_bits(d, prev_d29, prev_d30) & 0x1u) d |= 0x2u;
  return d;
}

}  // namespace deepnav::lnav
