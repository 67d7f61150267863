#include "signals/ca_code.hpp"

#include <stdexcept>
#include <string>

namespace deepnav {
namespace {

// G2 phase-selector taps per PRN (IS-GPS-200 Table 3-Ia), 1-based register stages.
constexpr std::array<std::array<int, 2>, 32> kG2Taps = {{
    {2, 6}, {3, 7}, {4, 8}, {5, 9}, {1, 9},  {2, 10}, {1, 8}, {2, 9}, {3, 10}, {2, 3}, {3, 4},
    {5, 6}, {6, 7}, {7, 8}, {8, 9}, {9, 10}, {1, 4},  {2, 5}, {3, 6}, {4, 7},  {5, 8}, {6, 9},
    {1, 3}, {4, 6}, {5, 7}, {6, 8}, {7, 9},  {8, 10}, {1, 6}, {2, 7}, {3, 8},  {4, 9},
}};

CaCodeChips to_chips(const CaCodeBits& bits) {
  CaCodeChips chips{};
  for (std::size_t i = 0; i < bits.size(); ++i) chips[i] = bits[i] ? -1 : 1;
  return chips;
}

std::array<CaCodeChips, 32> all_chips() {
  std::array<CaCodeChips, 32> table{};
  for (int prn = 1; prn <= 32; ++prn) table[prn - 1] = to_chips(ca_code_bits(prn));
  return table;
}

}  // namespace

CaCodeBits ca_code_bits(int prn) {
  if (prn < 1 || prn > 32) throw std::invalid_argument("C/A code: PRN " + std::to_string(prn) + " is not in 1..32");
  // Stage i of a register is element i-1; both start all ones.
  std::array<std::uint8_t, 10> g1{}, g2{};
  g1.fill(1);
  g2.fill(1);
  const auto [t1, t2] = kG2Taps[prn - 1];
  CaCodeBits out{};
  for (auto& chip : out) {
    chip = static_cast<std::uint8_t>(g1[9] ^ g2[t1 - 1] ^ g2[t2 - 1]);
    const auto g1_feedback = static_cast<std::uint8_t>(g1[2] ^ g1[9]);  // 1 + x^3 + x^10
    const auto g2_feedback =
        static_cast<std::uint8_t>(g2[1] ^ g2[2] ^ g2[5] ^ g2[7] ^ g2[8] ^ g2[9]);  // 1+x2+x3+x6+x8+x9+x10
    for (int i = 9; i > 0; --i) {
      g1[i] = g1[i - 1];
      g2[i] = g2[i - 1];
    }
    g1[0] = g1_feedback;
    g2[0] = g2_feedback;
  }
  return out;
}

const CaCodeChips& ca_code_chips(int prn) {
  static const std::array<CaCodeChips, 32> table = all_chips();
  if (prn < 1 || prn > 32) throw std::invalid_argument("C/A code: PRN " + std::to_string(prn) + " is not in 1..32");
  return table[prn - 1];
}

}  // namespace deepnav
