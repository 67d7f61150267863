#include "receiver/correlator.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <functional>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#if defined(__x86_64__)
// GCC 12 reports the deliberately undefined lanes of some AVX-512 intrinsics as
// (maybe-)uninitialized; the diagnostic points into the header, so it is silenced there only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif

namespace deepnav {
namespace {

constexpr int kRun = 4096;                 // samples per run: phases restart exactly at each run
constexpr int kCarrierBits = 21;           // carrier phase accumulator: 1 cycle = 2^21
constexpr double kCarrierOne = 2097152.0;  // 2^21
constexpr int kCodeFracBits = 27;          // code position: chips with 27 fraction bits
constexpr double kCodeOne = 134217728.0;   // 2^27
constexpr int kTapFracBits = 11;           // tap offsets: chips with 11 fraction bits
constexpr std::int64_t kCodeWrap = std::int64_t{1023} << kCodeFracBits;
constexpr double kPeriodChips = 1023.0;
constexpr int kPad = 64;   // code table chips before 0 and after 1022 (window loads, tap offsets)
constexpr int kTaps = 6;   // early, prompt, late, very early, very late, noise
constexpr int kNoise = 5;
constexpr int kSmallBits = 7;  // |I|, |Q| <= 127: exact products (see the header)

/// Everything a kernel needs that does not change within a call.
struct Setup {
  const std::int16_t* cos_tab;  // 32 entries
  const std::int16_t* sin_tab;
  const std::int16_t* code16;  // code levels, index = chip (valid for -kPad .. 1022 + kPad)
  const std::int16_t* noise16;
  const std::int8_t* code8;
  const std::int8_t* noise8;
  int taps;  // 3 (E/P/L) or 5 (with VE/VL); the noise tap is always there
  int h;     // whole chips the widest tap reaches beyond the prompt (>= 1)
  std::int16_t d[5];  // tap offsets in 2^-11 chip: E, P (0), L, VE, VL
};

/// Phases at the first sample of a run.
struct Run {
  std::uint32_t phi0, dphi;  // carrier, 2^21 per cycle (bits above 20 are ignored)
  std::int64_t pos0;         // prompt position in [0, 1023 * 2^27)
  std::int64_t inc;          // code step, 2^27 per chip
};

using Acc = std::int64_t[kTaps][2];

/// A run's samples: interleaved, and planar I and Q when the caller prepared them.
struct Input {
  const Sample* x;
  const std::int16_t* i;  // nullptr: deinterleave here
  const std::int16_t* q;
  Input at(int k) const { return {x + k, i ? i + k : nullptr, q ? q + k : nullptr}; }
};

// ---------------------------------------------------------------------------------------
// Tables.

/// Carrier tables for one amplitude: cos/sin at (p + 1/2) * 2 pi / 32, built from one
/// quarter wave so that every entry has an exact mirror (the AVX2 kernel looks up the
/// quarter wave and applies the signs itself).
struct CarrierTable {
  std::array<std::int16_t, 8> quarter;
  std::array<std::int16_t, 32> cos_tab, sin_tab;
  double scale;  // sums in sample units = integer sums * scale
};

CarrierTable make_carrier_table(double amplitude, double scale) {
  CarrierTable t{};
  for (int r = 0; r < 8; ++r)
    t.quarter[static_cast<std::size_t>(r)] = static_cast<std::int16_t>(std::lround(amplitude * std::cos((r + 0.5) * M_PI / 16.0)));
  for (int p = 0; p < 32; ++p) {
    const int q = p >> 3, r = p & 7;
    const std::int16_t m = t.quarter[static_cast<std::size_t>(r)], mm = t.quarter[static_cast<std::size_t>(7 - r)];
    const std::int16_t c[4] = {m, static_cast<std::int16_t>(-mm), static_cast<std::int16_t>(-m), mm};
    const std::int16_t s[4] = {mm, m, static_cast<std::int16_t>(-mm), static_cast<std::int16_t>(-m)};
    t.cos_tab[static_cast<std::size_t>(p)] = c[q];
    t.sin_tab[static_cast<std::size_t>(p)] = s[q];
  }
  t.scale = scale;
  return t;
}

/// Index b <= 7: inputs within +-(2^b - 1), amplitude 23170 / 2^b (|I c + Q s| <=
/// sqrt(2) 2^b A < 2^15). Index 8: larger inputs, products rounded by 2^15, amplitude 23000 (the two
/// rounded products add to at most sqrt(2) 23000 + 1 < 2^15).
const CarrierTable& carrier_table(int bits) {
  static const std::array<CarrierTable, kSmallBits + 2> tables = [] {
    std::array<CarrierTable, kSmallBits + 2> t{};
    for (int b = 0; b <= kSmallBits; ++b) {
      const double a = std::floor(23170.0 / std::ldexp(1.0, b));
      t[static_cast<std::size_t>(b)] = make_carrier_table(a, 1.0 / a);
    }
    t[kSmallBits + 1] = make_carrier_table(23000.0, 32768.0 / 23000.0);
    return t;
  }();
  return tables[static_cast<std::size_t>(std::min(bits, kSmallBits + 1))];
}

/// Code levels (+-1) as int16 and int8 over chips -kPad .. 1022 + kPad.
struct CodeTable {
  alignas(64) std::int16_t l16[1023 + 2 * kPad];
  alignas(64) std::int8_t l8[1023 + 2 * kPad];
  explicit CodeTable(const CaCodeChips& code) {
    for (int c = -kPad; c < 1023 + kPad; ++c) {
      const std::int8_t v = code[static_cast<std::size_t>((c + 1023) % 1023)];
      l16[c + kPad] = v;
      l8[c + kPad] = v;
    }
  }
};

/// The table of a code. A receiver interleaves its channels over the same block, so each
/// thread keeps the tables of ca_code_chips()'s 32 constant codes, and of the last 64 other
/// codes it saw, keyed by address and checked against a copy of the chips (a caller may
/// reuse an address for another code).
const CodeTable& table_for(const CaCodeChips& code) {
  static const CaCodeChips* const kFirst = &ca_code_chips(1);
  static const CaCodeChips* const kLast = &ca_code_chips(32);
  if (std::less_equal<>()(kFirst, &code) && std::less_equal<>()(&code, kLast)) {
    // One of the 32 constant codes: its own slot, no search and no comparison.
    thread_local std::array<std::unique_ptr<CodeTable>, 32> constant_tables;
    auto& table = constant_tables[static_cast<std::size_t>(&code - kFirst)];
    if (!table) table = std::make_unique<CodeTable>(code);
    return *table;
  }
  struct Entry {
    const CaCodeChips* key = nullptr;
    CaCodeChips chips{};
    std::unique_ptr<CodeTable> table;
  };
  constexpr int kEntries = 64;
  thread_local std::array<Entry, kEntries> cache;
  thread_local int next = 0;
  for (Entry& e : cache) {
    if (e.key == &code) {
      if (e.chips != code) {
        e.chips = code;
        e.table = std::make_unique<CodeTable>(code);
      }
      return *e.table;
    }
  }
  Entry& e = cache[static_cast<std::size_t>(next)];
  next = (next + 1) % kEntries;
  e.key = &code;
  e.chips = code;
  e.table = std::make_unique<CodeTable>(code);
  return *e.table;
}

// ---------------------------------------------------------------------------------------
// Portable kernel: the definition of the integers every kernel computes.

inline std::int16_t mulhrs(std::int16_t a, std::int16_t b) {
  return static_cast<std::int16_t>((static_cast<std::int32_t>(a) * b + 0x4000) >> 15);
}

/// Bits of the largest |I| or |Q|: every sample within +-(2^b - 1) (|-32768| gives 16).
int sample_bits_portable(const Sample* x, int n) {
  unsigned m = 0;
  const auto* iq = reinterpret_cast<const std::int16_t*>(x);
  for (int k = 0; k < 2 * n; ++k) m |= static_cast<unsigned>(std::abs(static_cast<int>(iq[k])));
  return std::bit_width(m);
}

inline std::int16_t level(const std::int16_t* table, std::int64_t chip) {
  if (chip >= -kPad && chip < 1023 + kPad) return table[chip];
  return table[((chip % 1023) + 1023) % 1023];
}

template <bool kSmall, int kT, bool kNear>
void kernel_portable_impl(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
  const Sample* x = in.x;
  // kNear: every tap within kPad chips, so a chip index never leaves the padded table.
  const auto chip_level = [](const std::int16_t* table, std::int64_t chip) {
    return kNear ? table[chip] : level(table, chip);
  };
  std::int64_t offset[kT];
  for (int t = 0; t < kT; ++t) offset[t] = std::int64_t{su.d[t]} << (kCodeFracBits - kTapFracBits);
  std::int32_t sums[kTaps][2] = {};  // a run adds at most 4096 * 2^15 < 2^31
  std::int64_t pos = run.pos0;
  std::uint32_t phi = run.phi0;
  for (int k = 0; k < m; ++k, phi += run.dphi) {
    const unsigned p = (phi >> 16) & 31u;
    const std::int16_t c = su.cos_tab[p], s = su.sin_tab[p];
    const std::int16_t i = x[k].real(), q = x[k].imag();
    std::int32_t re, im;
    if constexpr (kSmall) {
      re = static_cast<std::int16_t>(i * c + q * s);
      im = static_cast<std::int16_t>(q * c - i * s);
    } else {
      re = static_cast<std::int16_t>(mulhrs(i, c) + mulhrs(q, s));
      im = static_cast<std::int16_t>(mulhrs(q, c) - mulhrs(i, s));
    }
    for (int t = 0; t < kT; ++t) {
      const std::int16_t l = chip_level(su.code16, (pos + offset[t]) >> kCodeFracBits);
      sums[t][0] += re * l;
      sums[t][1] += im * l;
    }
    const std::int16_t l = chip_level(su.noise16, pos >> kCodeFracBits);
    sums[kNoise][0] += re * l;
    sums[kNoise][1] += im * l;
    pos += run.inc;
    if (pos >= kCodeWrap) pos -= kCodeWrap;
  }
  for (int t = 0; t < kTaps; ++t) {
    acc[t][0] += sums[t][0];
    acc[t][1] += sums[t][1];
  }
}

template <bool kSmall>
void kernel_portable(const Input& x, int m, const Run& run, const Setup& su, Acc& acc) {
  const bool near = su.h <= kPad;
  if (su.taps == 3)
    (near ? kernel_portable_impl<kSmall, 3, true> : kernel_portable_impl<kSmall, 3, false>)(x, m, run, su, acc);
  else
    (near ? kernel_portable_impl<kSmall, 5, true> : kernel_portable_impl<kSmall, 5, false>)(x, m, run, su, acc);
}

#if defined(__x86_64__)
// ---------------------------------------------------------------------------------------
// AVX-512 (BW + VNNI): 32 samples per iteration, planar int16 re/im in natural order.
#define DEEPNAV_AVX512 __attribute__((target("avx512f,avx512bw,avx512vnni")))

DEEPNAV_AVX512 int sample_bits_avx512(const Sample* x, int n) {
  // OR of |I|, |Q| (pabsw gives 0x8000 for -32768: 16 bits), in two independent chains.
  const auto* p = reinterpret_cast<const std::int32_t*>(x);
  __m512i acc0 = _mm512_setzero_si512(), acc1 = acc0;
  int k = 0;
  for (; k + 64 <= n; k += 64) {
    const __m512i a0 = _mm512_abs_epi16(_mm512_loadu_si512(p + k));
    const __m512i a1 = _mm512_abs_epi16(_mm512_loadu_si512(p + k + 16));
    const __m512i a2 = _mm512_abs_epi16(_mm512_loadu_si512(p + k + 32));
    const __m512i a3 = _mm512_abs_epi16(_mm512_loadu_si512(p + k + 48));
    acc0 = _mm512_ternarylogic_epi32(acc0, a0, a1, 0xFE);  // a | b | c
    acc1 = _mm512_ternarylogic_epi32(acc1, a2, a3, 0xFE);
  }
  for (; k < n; k += 16) {  // masked loads: the missing samples read as 0, which changes nothing
    const __m512i v =
        _mm512_maskz_loadu_epi32(static_cast<__mmask16>(0xFFFFu >> (16 - std::min(n - k, 16))), p + k);
    acc0 = _mm512_or_si512(acc0, _mm512_abs_epi16(v));
  }
  alignas(64) std::uint16_t w[32];
  _mm512_store_si512(w, _mm512_or_si512(acc0, acc1));
  unsigned m = 0;
  for (std::uint16_t v : w) m |= v;
  return std::bit_width(m);
}

/// 0, 2, ..., 62: with permutex2var, word k of the result is word 2k of the pair (a, b) (I
/// of 32 interleaved samples); the odd words (Q) take these plus one.
alignas(64) constexpr std::array<std::uint16_t, 32> kEvenWords = [] {
  std::array<std::uint16_t, 32> e{};
  for (std::size_t k = 0; k < 32; ++k) e[k] = static_cast<std::uint16_t>(2 * k);
  return e;
}();

template <int kT, bool kSmall, bool kPlanar>
DEEPNAV_AVX512 void kernel_avx512(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
  const auto* src = reinterpret_cast<const std::int32_t*>(in.x);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i sixteen = _mm512_set1_epi32(16);
  // Word k of the result is word 2k (I) / 2k+1 (Q, and the high halves of the dwords) of
  // the pair (a, b): deinterleaves 32 samples.
  const __m512i even = _mm512_load_si512(kEvenWords.data());
  const __m512i odd = _mm512_add_epi16(even, _mm512_set1_epi16(1));
  const __m512i cos_t = _mm512_loadu_si512(su.cos_tab), sin_t = _mm512_loadu_si512(su.sin_tab);

  // Carrier phases of samples 0..15 and 16..31; the table index is bits 16..20.
  const __m512i dphi = _mm512_set1_epi32(static_cast<int>(run.dphi));
  __m512i phi_a = _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(run.phi0)), _mm512_mullo_epi32(lane, dphi));
  __m512i phi_b = _mm512_add_epi32(phi_a, _mm512_mullo_epi32(sixteen, dphi));
  const __m512i phi_step = _mm512_slli_epi32(dphi, 5);

  // Code positions of samples 0..31 relative to the block's first chip minus h, 2^27 per
  // chip: the high words hold the positions in 2^-11 chip (the tap offsets' unit).
  const auto inc = static_cast<std::uint32_t>(run.inc);
  const __m512i inc_v = _mm512_set1_epi32(static_cast<int>(inc));
  const __m512i off_a =
      _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(static_cast<std::uint32_t>(su.h) << kCodeFracBits)),
                       _mm512_mullo_epi32(lane, inc_v));
  const __m512i off_b = _mm512_add_epi32(off_a, _mm512_mullo_epi32(sixteen, inc_v));
  const __m512i d_e = _mm512_set1_epi16(su.d[0]), d_l = _mm512_set1_epi16(su.d[2]);
  const __m512i d_ve = _mm512_set1_epi16(su.d[3]), d_vl = _mm512_set1_epi16(su.d[4]);

  // Named accumulators (not arrays): GCC keeps arrays of vectors in memory as well.
  __m512i e_re = _mm512_setzero_si512(), e_im = e_re, p_re = e_re, p_im = e_re, l_re = e_re, l_im = e_re;
  __m512i ve_re = e_re, ve_im = e_re, vl_re = e_re, vl_im = e_re, n_re = e_re, n_im = e_re;

  std::int64_t pos = run.pos0;
  const std::int64_t block_inc = run.inc * 32;
  for (int k = 0; k < m; k += 32) {
    __m512i i, q;
    if constexpr (kPlanar) {
      if (const int left = m - k; left >= 32) [[likely]] {
        i = _mm512_loadu_si512(in.i + k);
        q = _mm512_loadu_si512(in.q + k);
      } else {  // masked loads: the missing samples are zero and add nothing
        const auto mask = static_cast<__mmask32>(0xFFFFFFFFu >> (32 - left));
        i = _mm512_maskz_loadu_epi16(mask, in.i + k);
        q = _mm512_maskz_loadu_epi16(mask, in.q + k);
      }
    } else {
      __m512i x0, x1;
      if (const int left = m - k; left >= 32) [[likely]] {
        x0 = _mm512_loadu_si512(src + k);
        x1 = _mm512_loadu_si512(src + k + 16);
      } else {  // masked loads: the missing samples are zero and add nothing
        x0 = _mm512_maskz_loadu_epi32(static_cast<__mmask16>(0xFFFFu >> (16 - std::min(left, 16))), src + k);
        x1 = _mm512_maskz_loadu_epi32(static_cast<__mmask16>(0xFFFFu >> (16 - std::max(left - 16, 0))), src + k + 16);
      }
      i = _mm512_permutex2var_epi16(x0, even, x1);
      q = _mm512_permutex2var_epi16(x0, odd, x1);
    }

    const __m512i pidx = _mm512_permutex2var_epi16(phi_a, odd, phi_b);
    phi_a = _mm512_add_epi32(phi_a, phi_step);
    phi_b = _mm512_add_epi32(phi_b, phi_step);
    const __m512i c = _mm512_permutexvar_epi16(pidx, cos_t), s = _mm512_permutexvar_epi16(pidx, sin_t);
    __m512i re, im;
    if constexpr (kSmall) {
      re = _mm512_add_epi16(_mm512_mullo_epi16(i, c), _mm512_mullo_epi16(q, s));
      im = _mm512_sub_epi16(_mm512_mullo_epi16(q, c), _mm512_mullo_epi16(i, s));
    } else {
      re = _mm512_add_epi16(_mm512_mulhrs_epi16(i, c), _mm512_mulhrs_epi16(q, s));
      im = _mm512_sub_epi16(_mm512_mulhrs_epi16(q, c), _mm512_mulhrs_epi16(i, s));
    }

    const auto first = static_cast<int>(pos >> kCodeFracBits);
    const __m512i frac = _mm512_set1_epi32(static_cast<int>(pos & ((std::int64_t{1} << kCodeFracBits) - 1)));
    const __m512i w = _mm512_permutex2var_epi16(_mm512_add_epi32(frac, off_a), odd, _mm512_add_epi32(frac, off_b));
    const __m512i win = _mm512_loadu_si512(su.code16 + first - su.h);
    const __m512i nwin = _mm512_loadu_si512(su.noise16 + first - su.h);
#define DEEPNAV_TAP(IDX, WIN, RE, IM)                  \
  {                                                    \
    const __m512i code = _mm512_permutexvar_epi16(IDX, WIN); \
    RE = _mm512_dpwssd_epi32(RE, re, code);            \
    IM = _mm512_dpwssd_epi32(IM, im, code);            \
  }
    const __m512i idx_p = _mm512_srli_epi16(w, kTapFracBits);
    DEEPNAV_TAP(idx_p, win, p_re, p_im)
    DEEPNAV_TAP(idx_p, nwin, n_re, n_im)  // the noise tap shares the prompt's timing
    DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_e), kTapFracBits), win, e_re, e_im)
    DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_l), kTapFracBits), win, l_re, l_im)
    if constexpr (kT == 5) {
      DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_ve), kTapFracBits), win, ve_re, ve_im)
      DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_vl), kTapFracBits), win, vl_re, vl_im)
    }
#undef DEEPNAV_TAP
    pos += block_inc;
    if (pos >= kCodeWrap) pos -= kCodeWrap;
  }
  // A run adds at most 128 * 2 * 2^15 per lane: int32 lanes and their sum cannot overflow.
#define DEEPNAV_ADD(T, RE, IM)                \
  acc[T][0] += _mm512_reduce_add_epi32(RE); \
  acc[T][1] += _mm512_reduce_add_epi32(IM);
  DEEPNAV_ADD(0, e_re, e_im)
  DEEPNAV_ADD(1, p_re, p_im)
  DEEPNAV_ADD(2, l_re, l_im)
  if constexpr (kT == 5) {
    DEEPNAV_ADD(3, ve_re, ve_im)
    DEEPNAV_ADD(4, vl_re, vl_im)
  }
  DEEPNAV_ADD(kNoise, n_re, n_im)
#undef DEEPNAV_ADD
}

// ---------------------------------------------------------------------------------------
// AVX2: 16 samples per iteration. Word 2j of a register holds sample j, word 2j+1 sample
// 8 + j, so that 16-bit halves of two dword registers interleave with one blend.
#define DEEPNAV_AVX2 __attribute__((target("avx2")))

DEEPNAV_AVX2 int sample_bits_avx2(const Sample* x, int n) {
  const auto* p = reinterpret_cast<const std::int32_t*>(x);
  __m256i acc0 = _mm256_setzero_si256(), acc1 = acc0;
  int k = 0;
  for (; k + 32 <= n; k += 32) {
    const auto* v = reinterpret_cast<const __m256i*>(p + k);
    acc0 = _mm256_or_si256(acc0, _mm256_or_si256(_mm256_abs_epi16(_mm256_loadu_si256(v)),
                                                 _mm256_abs_epi16(_mm256_loadu_si256(v + 1))));
    acc1 = _mm256_or_si256(acc1, _mm256_or_si256(_mm256_abs_epi16(_mm256_loadu_si256(v + 2)),
                                                 _mm256_abs_epi16(_mm256_loadu_si256(v + 3))));
  }
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (; k < n; k += 8) {  // masked loads: the missing samples read as 0, which changes nothing
    const __m256i v = _mm256_maskload_epi32(p + k, _mm256_cmpgt_epi32(_mm256_set1_epi32(n - k), lane));
    acc0 = _mm256_or_si256(acc0, _mm256_abs_epi16(v));
  }
  alignas(32) std::uint16_t w[16];
  _mm256_store_si256(reinterpret_cast<__m256i*>(w), _mm256_or_si256(acc0, acc1));
  unsigned m = 0;
  for (std::uint16_t v : w) m |= v;
  return std::bit_width(m);
}

/// Adds the int32 lanes of v / 256 to out and clears v (the lanes hold multiples of 256).
DEEPNAV_AVX2 inline void drain(__m256i& v, std::int64_t& out) {
  alignas(32) std::int32_t lanes[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), v);
  std::int64_t sum = 0;
  for (std::int32_t l : lanes) sum += l;
  out += sum / 256;
  v = _mm256_setzero_si256();
}

template <int kT, bool kSmall>
DEEPNAV_AVX2 void kernel_avx2(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
  const Sample* x = in.x;
  const auto* src = reinterpret_cast<const std::int32_t*>(x);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i eight = _mm256_set1_epi32(8);
  // Quarter-wave table (entries 0..7 of the cos table, 8 words) for pshufb, and the map from
  // the low 4 bits of the phase index to the byte offset of its entry (7 - r in odd quadrants).
  const __m256i qtab = _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(su.cos_tab)));
  const __m256i map = _mm256_setr_epi8(0, 2, 4, 6, 8, 10, 12, 14, 14, 12, 10, 8, 6, 4, 2, 0, 0, 2, 4, 6, 8, 10, 12, 14,
                                       14, 12, 10, 8, 6, 4, 2, 0);
  const __m256i hi_byte = _mm256_set1_epi16(0x0100);
  const __m256i mirror = _mm256_set1_epi16(0x0E0E);
  const __m256i five_bits = _mm256_set1_epi16(31);
  const __m256i one = _mm256_set1_epi16(1);
  const __m256i dup = _mm256_set1_epi16(0x0101);

  const __m256i dphi = _mm256_set1_epi32(static_cast<int>(run.dphi));
  __m256i phi_a = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(run.phi0)), _mm256_mullo_epi32(lane, dphi));
  __m256i phi_b = _mm256_add_epi32(phi_a, _mm256_mullo_epi32(eight, dphi));
  const __m256i phi_step = _mm256_slli_epi32(dphi, 4);

  const auto inc = static_cast<std::uint32_t>(run.inc);
  const __m256i inc_v = _mm256_set1_epi32(static_cast<int>(inc));
  const __m256i off_a =
      _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(static_cast<std::uint32_t>(su.h) << kCodeFracBits)),
                       _mm256_mullo_epi32(lane, inc_v));
  const __m256i off_b = _mm256_add_epi32(off_a, _mm256_mullo_epi32(eight, inc_v));
  const __m256i zero_low = _mm256_set1_epi16(0x0080);  // pshufb index with bit 7 set gives 0
  const __m256i d_e = _mm256_set1_epi16(su.d[0]), d_l = _mm256_set1_epi16(su.d[2]);
  const __m256i d_ve = _mm256_set1_epi16(su.d[3]), d_vl = _mm256_set1_epi16(su.d[4]);

  // Named accumulators (not arrays): GCC keeps arrays of vectors in memory as well.
  __m256i e_re = _mm256_setzero_si256(), e_im = e_re, p_re = e_re, p_im = e_re, l_re = e_re, l_im = e_re;
  __m256i ve_re = e_re, ve_im = e_re, vl_re = e_re, vl_im = e_re, n_re = e_re, n_im = e_re;

  std::int64_t pos = run.pos0;
  const std::int64_t block_inc = run.inc * 16;
  // Two passes per chunk of 64 blocks, so that neither needs more than the 16 registers:
  // carrier wipe-off into re/im buffers, then the taps.
  alignas(32) std::int16_t re_buf[64 * 16], im_buf[64 * 16];
  for (int k0 = 0; k0 < m; k0 += 64 * 16) {
    const int k_end = std::min(m, k0 + 64 * 16);
    for (int k = k0; k < k_end; k += 16) {
      __m256i x0, x1;
      if (const int left = m - k; left >= 16) [[likely]] {
        x0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + k));
        x1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + k + 8));
      } else {  // masked loads: the missing samples are zero and add nothing
        x0 = _mm256_maskload_epi32(src + k, _mm256_cmpgt_epi32(_mm256_set1_epi32(left), lane));
        x1 = _mm256_maskload_epi32(src + k + 8, _mm256_cmpgt_epi32(_mm256_set1_epi32(left - 8), lane));
      }
      const __m256i i = _mm256_blend_epi16(x0, _mm256_slli_epi32(x1, 16), 0xAA);
      const __m256i q = _mm256_blend_epi16(_mm256_srli_epi32(x0, 16), x1, 0xAA);

      // Phase index p (5 bits) per word; quadrant = p >> 3, r = p & 7.
      const __m256i p = _mm256_and_si256(_mm256_blend_epi16(_mm256_srli_epi32(phi_a, 16), phi_b, 0xAA), five_bits);
      phi_a = _mm256_add_epi32(phi_a, phi_step);
      phi_b = _mm256_add_epi32(phi_b, phi_step);
      const __m256i cidx = _mm256_add_epi16(_mm256_shuffle_epi8(map, _mm256_mullo_epi16(p, dup)), hi_byte);
      const __m256i mag_c = _mm256_shuffle_epi8(qtab, cidx);
      const __m256i mag_s = _mm256_shuffle_epi8(qtab, _mm256_xor_si256(cidx, mirror));
      // Signs: sin < 0 in quadrants 2, 3 (bit 4), cos < 0 in quadrants 1, 2 (bit 3 xor bit 4);
      // bit 0 set keeps the sign words non-zero for psignw.
      const __m256i sgn_s = _mm256_or_si256(_mm256_slli_epi16(p, 11), one);
      const __m256i sgn_c = _mm256_xor_si256(sgn_s, _mm256_slli_epi16(p, 12));
      const __m256i c = _mm256_sign_epi16(mag_c, sgn_c), s = _mm256_sign_epi16(mag_s, sgn_s);
      __m256i re, im;
      if constexpr (kSmall) {
        re = _mm256_add_epi16(_mm256_mullo_epi16(i, c), _mm256_mullo_epi16(q, s));
        im = _mm256_sub_epi16(_mm256_mullo_epi16(q, c), _mm256_mullo_epi16(i, s));
      } else {
        re = _mm256_add_epi16(_mm256_mulhrs_epi16(i, c), _mm256_mulhrs_epi16(q, s));
        im = _mm256_sub_epi16(_mm256_mulhrs_epi16(q, c), _mm256_mulhrs_epi16(i, s));
      }
      _mm256_store_si256(reinterpret_cast<__m256i*>(re_buf + (k - k0)), re);
      _mm256_store_si256(reinterpret_cast<__m256i*>(im_buf + (k - k0)), im);
    }
    for (int k = k0; k < k_end; k += 16) {
      const __m256i re = _mm256_load_si256(reinterpret_cast<const __m256i*>(re_buf + (k - k0)));
      const __m256i im = _mm256_load_si256(reinterpret_cast<const __m256i*>(im_buf + (k - k0)));
      const auto first = static_cast<int>(pos >> kCodeFracBits);
      const __m256i frac = _mm256_set1_epi32(static_cast<int>(pos & ((std::int64_t{1} << kCodeFracBits) - 1)));
      const __m256i w =
          _mm256_blend_epi16(_mm256_srli_epi32(_mm256_add_epi32(frac, off_a), 16), _mm256_add_epi32(frac, off_b), 0xAA);
      const __m256i win =
          _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(su.code8 + first - su.h)));
      const __m256i nwin =
          _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(su.noise8 + first - su.h)));
      // Index words: high byte the chip (position >> 11), low byte 0x80 so that pshufb puts
      // the level (+-1) in the high byte: code words of +-256.
#define DEEPNAV_IDX(D) _mm256_or_si256(_mm256_srli_epi16(D, kTapFracBits - 8), zero_low)
#define DEEPNAV_TAP(IDX, WIN, RE, IM)                                   \
  {                                                                     \
    const __m256i code = _mm256_shuffle_epi8(WIN, IDX);                 \
    RE = _mm256_add_epi32(RE, _mm256_madd_epi16(re, code));             \
    IM = _mm256_add_epi32(IM, _mm256_madd_epi16(im, code));             \
  }
      const __m256i idx_p = DEEPNAV_IDX(w);
      DEEPNAV_TAP(idx_p, win, p_re, p_im)
      DEEPNAV_TAP(idx_p, nwin, n_re, n_im)  // the noise tap shares the prompt's timing
      DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_e)), win, e_re, e_im)
      DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_l)), win, l_re, l_im)
      if constexpr (kT == 5) {
        DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_ve)), win, ve_re, ve_im)
        DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_vl)), win, vl_re, vl_im)
      }
#undef DEEPNAV_TAP
#undef DEEPNAV_IDX
      pos += block_inc;
      if (pos >= kCodeWrap) pos -= kCodeWrap;
    }
    // Each madd adds up to 2^24 per lane: 64 iterations stay within int32.
    drain(e_re, acc[0][0]);
    drain(e_im, acc[0][1]);
    drain(p_re, acc[1][0]);
    drain(p_im, acc[1][1]);
    drain(l_re, acc[2][0]);
    drain(l_im, acc[2][1]);
    if constexpr (kT == 5) {
      drain(ve_re, acc[3][0]);
      drain(ve_im, acc[3][1]);
      drain(vl_re, acc[4][0]);
      drain(vl_im, acc[4][1]);
    }
    drain(n_re, acc[kNoise][0]);
    drain(n_im, acc[kNoise][1]);
  }
}
#endif

using KernelFn = void (*)(const Input&, int, const Run&, const Setup&, Acc&);

KernelFn pick_kernel(CorrelatorKernel kernel, int taps, bool small, bool planar) {
  switch (kernel) {
#if defined(__x86_64__)
    case CorrelatorKernel::avx512:
      if (planar) {
        if (taps == 3) return small ? kernel_avx512<3, true, true> : kernel_avx512<3, false, true>;
        return small ? kernel_avx512<5, true, true> : kernel_avx512<5, false, true>;
      }
      if (taps == 3) return small ? kernel_avx512<3, true, false> : kernel_avx512<3, false, false>;
      return small ? kernel_avx512<5, true, false> : kernel_avx512<5, false, false>;
    case CorrelatorKernel::avx2:
      if (taps == 3) return small ? kernel_avx2<3, true> : kernel_avx2<3, false>;
      return small ? kernel_avx2<5, true> : kernel_avx2<5, false>;
#endif
    default:
      return small ? kernel_portable<true> : kernel_portable<false>;
  }
}

int sample_bits(CorrelatorKernel kernel, const Sample* x, int n) {
  switch (kernel) {
#if defined(__x86_64__)
    case CorrelatorKernel::avx512:
      return sample_bits_avx512(x, n);
    case CorrelatorKernel::avx2:
      return sample_bits_avx2(x, n);
#endif
    default:
      return sample_bits_portable(x, n);
  }
}

/// Window width (chips) of a SIMD kernel's code lookup and samples per block.
struct Geometry {
  int window, block;
};
Geometry geometry(CorrelatorKernel kernel) {
  return kernel == CorrelatorKernel::avx512 ? Geometry{32, 32} : Geometry{16, 16};
}

double wrap_chips(double chips) {
  double c = std::fmod(chips, kPeriodChips);
  if (c < 0.0) c += kPeriodChips;
  return c;
}

}  // namespace

#if defined(__x86_64__)
/// Deinterleaves whole groups of 32 samples; returns how many samples it did.
DEEPNAV_AVX512 int deinterleave_avx512(const Sample* x, int n, std::int16_t* i, std::int16_t* q) {
  const auto* src = reinterpret_cast<const std::int32_t*>(x);
  const __m512i even = _mm512_load_si512(kEvenWords.data());
  const __m512i odd = _mm512_add_epi16(even, _mm512_set1_epi16(1));
  int k = 0;
  for (; k + 32 <= n; k += 32) {
    const __m512i x0 = _mm512_loadu_si512(src + k), x1 = _mm512_loadu_si512(src + k + 16);
    _mm512_storeu_si512(i + k, _mm512_permutex2var_epi16(x0, even, x1));
    _mm512_storeu_si512(q + k, _mm512_permutex2var_epi16(x0, odd, x1));
  }
  return k;
}
#endif

void deinterleave(const Sample* x, int n, std::int16_t* i, std::int16_t* q) {
  int k = 0;
#if defined(__x86_64__)
  if (best_correlator_kernel() == CorrelatorKernel::avx512) k = deinterleave_avx512(x, n, i, q);
#endif
  for (; k < n; ++k) {
    i[k] = x[k].real();
    q[k] = x[k].imag();
  }
}

void prepare_for_correlation(SampleBlock& block) {
  const auto n = static_cast<int>(block.samples.size());
  block.magnitude_bits = sample_magnitude_bits(block.samples.data(), n);
  if (!correlator_reads_planar_input()) {
    block.planar.clear();
    return;
  }
  block.planar.resize(2 * block.samples.size());
  deinterleave(block.samples.data(), n, block.planar.data(), block.planar.data() + n);
}

bool correlator_reads_planar_input() { return best_correlator_kernel() == CorrelatorKernel::avx512; }

int sample_magnitude_bits(const Sample* samples, int n) {
  return n > 0 ? sample_bits(best_correlator_kernel(), samples, n) : 0;
}

std::vector<CorrelatorKernel> available_correlator_kernels() {
  std::vector<CorrelatorKernel> k{CorrelatorKernel::portable};
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx2")) k.push_back(CorrelatorKernel::avx2);
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vnni"))
    k.push_back(CorrelatorKernel::avx512);
#endif
  return k;
}

CorrelatorKernel best_correlator_kernel() {
  static const CorrelatorKernel best = available_correlator_kernels().back();
  return best;
}

CorrelatorSums correlate(const Sample* samples, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                         const CaCodeChips& noise_code) {
  return correlate(best_correlator_kernel(), CorrelatorInput{samples}, n, s, code, noise_code);
}

CorrelatorSums correlate(const CorrelatorInput& input, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                         const CaCodeChips& noise_code) {
  return correlate(best_correlator_kernel(), input, n, s, code, noise_code);
}

CorrelatorSums correlate(CorrelatorKernel kernel, const Sample* samples, int n, const CorrelatorSpan& s,
                         const CaCodeChips& code, const CaCodeChips& noise_code) {
  return correlate(kernel, CorrelatorInput{samples}, n, s, code, noise_code);
}

CorrelatorSums correlate(CorrelatorKernel kernel, const CorrelatorInput& input, int n, const CorrelatorSpan& s,
                         const CaCodeChips& code, const CaCodeChips& noise_code) {
  const Sample* samples = input.samples;
  CorrelatorSums out;
  if (n <= 0) return out;
  if (!(s.code_step_chips > 0.0 && s.code_step_chips <= 2.0))
    throw std::invalid_argument("correlate: code step per sample must be in (0, 2] chips, got " +
                                std::to_string(s.code_step_chips));
  const CodeTable& table = table_for(code);
  const CodeTable& noise_table = table_for(noise_code);
  const bool very = s.very_spacing_chips > 0.0;

  Setup su{};
  su.taps = very ? 5 : 3;
  const auto tap = [](double chips) {
    return static_cast<std::int16_t>(std::clamp<long long>(std::llround(chips * 2048.0), -32000, 32000));
  };
  su.d[0] = tap(0.5 * s.spacing_chips);
  su.d[1] = 0;
  su.d[2] = static_cast<std::int16_t>(-su.d[0]);
  su.d[3] = very ? tap(0.5 * s.very_spacing_chips) : std::int16_t{0};
  su.d[4] = static_cast<std::int16_t>(-su.d[3]);
  int reach = 0;
  for (int t = 0; t < su.taps; ++t) reach = std::max(reach, std::abs(static_cast<int>(su.d[t])));
  su.h = std::max(1, (reach + 2047) / 2048);
  su.code16 = table.l16 + kPad;
  su.noise16 = noise_table.l16 + kPad;
  su.code8 = table.l8 + kPad;
  su.noise8 = noise_table.l8 + kPad;
  const auto inc = static_cast<std::int64_t>(std::llround(s.code_step_chips * kCodeOne));

  // A SIMD kernel needs every tap of a block inside its window: the block's first
  // position (fraction < 1 chip) plus h chips either side plus (block - 1) steps.
  if (kernel != CorrelatorKernel::portable) {
    const Geometry g = geometry(kernel);
    const std::int64_t need = (std::int64_t{1} + 2 * su.h) * (std::int64_t{1} << kCodeFracBits) + (g.block - 1) * inc;
    if (need > (std::int64_t{g.window} << kCodeFracBits) || su.h > kPad / 2) kernel = CorrelatorKernel::portable;
  }

  if (s.magnitude_bits > 16) throw std::invalid_argument("correlate: magnitude_bits must be at most 16");
  const int bits = s.magnitude_bits >= 0 ? s.magnitude_bits : sample_bits(kernel, samples, n);
  const bool small = bits <= kSmallBits;
  const CarrierTable& ct = carrier_table(bits);
  su.cos_tab = ct.cos_tab.data();
  su.sin_tab = ct.sin_tab.data();
  const bool planar = input.i != nullptr && input.q != nullptr;
  const KernelFn fn = pick_kernel(kernel, su.taps, small, planar);
  const Input in{samples, planar ? input.i : nullptr, planar ? input.q : nullptr};

  const auto dphi = static_cast<std::uint32_t>(std::llround(s.carrier_step_cycles * kCarrierOne));
  Acc acc{};
  for (int k0 = 0; k0 < n; k0 += kRun) {
    const int m = std::min(kRun, n - k0);
    Run run{};
    const double carrier = s.carrier_phase_cycles + k0 * s.carrier_step_cycles;
    run.phi0 = static_cast<std::uint32_t>(std::llround((carrier - std::floor(carrier)) * kCarrierOne)) &
               ((1u << kCarrierBits) - 1u);
    run.dphi = dphi;
    run.pos0 = std::llround(wrap_chips(s.code_phase_chips + k0 * s.code_step_chips) * kCodeOne);
    if (run.pos0 >= kCodeWrap) run.pos0 -= kCodeWrap;
    run.inc = inc;
    fn(in.at(k0), m, run, su, acc);
  }
  const auto sum = [&](int t) {
    return std::complex<double>(static_cast<double>(acc[t][0]) * ct.scale, static_cast<double>(acc[t][1]) * ct.scale);
  };
  out.early = sum(0);
  out.prompt = sum(1);
  out.late = sum(2);
  if (very) {
    out.very_early = sum(3);
    out.very_late = sum(4);
  }
  out.noise = sum(kNoise);
  return out;
}

CorrelatorSums correlate_reference(const Sample* samples, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                                   const CaCodeChips& noise_code) {
  CorrelatorSums out;
  const auto level = [](const CaCodeChips& c, double chips) {
    return static_cast<double>(c[static_cast<std::size_t>(std::floor(wrap_chips(chips)))]);
  };
  const double half = 0.5 * s.spacing_chips, very_half = 0.5 * s.very_spacing_chips;
  for (int k = 0; k < n; ++k) {
    const double phase = s.carrier_phase_cycles + k * s.carrier_step_cycles;
    const std::complex<double> x(samples[k].real(), samples[k].imag());
    const std::complex<double> v = x * std::polar(1.0, -2.0 * M_PI * (phase - std::floor(phase)));
    const double chip = s.code_phase_chips + k * s.code_step_chips;
    out.early += v * level(code, chip + half);
    out.prompt += v * level(code, chip);
    out.late += v * level(code, chip - half);
    if (s.very_spacing_chips > 0.0) {
      out.very_early += v * level(code, chip + very_half);
      out.very_late += v * level(code, chip - very_half);
    }
    out.noise += v * level(noise_code, chip);
  }
  return out;
}

}  // namespace deepnav
