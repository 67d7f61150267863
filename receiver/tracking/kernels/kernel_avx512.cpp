// AVX-512 kernel (F + BW + VNNI), compiled with those instruction sets
// (receiver/CMakeLists.txt); called only on CPUs that have them.
#include "receiver/tracking/kernels/kernels.hpp"

#if defined(__x86_64__)
// GCC 12 reports the deliberately undefined lanes of some AVX-512 intrinsics as
// (maybe-)uninitialized; the diagnostic points into the header, so it is silenced there only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop

namespace deepnav::correlator_detail {
namespace {

// ---------------------------------------------------------------------------------------
// AVX-512 (BW + VNNI): 32 samples per iteration, planar int16 re/im in natural order.
int sample_bits_impl(const Sample* x, int n) {
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
        _mm512_maskz_loadu_epi32(static_cast<__mmask16>(0xFFFFu >> (16 - (n - k < 16 ? n - k : 16))), p + k);
    acc0 = _mm512_or_si512(acc0, _mm512_abs_epi16(v));
  }
  alignas(64) std::uint16_t w[32];
  _mm512_store_si512(w, _mm512_or_si512(acc0, acc1));
  unsigned m = 0;
  for (std::uint16_t v : w) m |= v;
  int b = 0;
  while (m >> b) ++b;
  return b;
}

/// 0, 2, ..., 62: with permutex2var, word k of the result is word 2k of the pair (a, b) (I
/// of 32 interleaved samples); the odd words (Q) take these plus one.
struct EvenWords {
  alignas(64) std::uint16_t w[32];
};
constexpr EvenWords kEvenWords = [] {
  EvenWords e{};
  for (int k = 0; k < 32; ++k) e.w[k] = static_cast<std::uint16_t>(2 * k);
  return e;
}();

template <int kT, bool kSmall, bool kPlanar, bool kN>
void kernel(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
  const auto* src = reinterpret_cast<const std::int32_t*>(in.x);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i sixteen = _mm512_set1_epi32(16);
  // Word k of the result is word 2k (I) / 2k+1 (Q, and the high halves of the dwords) of
  // the pair (a, b): deinterleaves 32 samples.
  const __m512i even = _mm512_load_si512(kEvenWords.w);
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
        x0 = _mm512_maskz_loadu_epi32(static_cast<__mmask16>(0xFFFFu >> (16 - (left < 16 ? left : 16))), src + k);
        x1 = _mm512_maskz_loadu_epi32(static_cast<__mmask16>(0xFFFFu >> (16 - (left > 16 ? left - 16 : 0))),
                                      src + k + 16);
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
#define DEEPNAV_TAP(IDX, WIN, RE, IM)                        \
  {                                                          \
    const __m512i code = _mm512_permutexvar_epi16(IDX, WIN); \
    RE = _mm512_dpwssd_epi32(RE, re, code);                  \
    IM = _mm512_dpwssd_epi32(IM, im, code);                  \
  }
    const __m512i idx_p = _mm512_srli_epi16(w, kTapFracBits);
    DEEPNAV_TAP(idx_p, win, p_re, p_im)
    if constexpr (kN) DEEPNAV_TAP(idx_p, nwin, n_re, n_im)  // the noise tap shares the prompt's timing
    DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_e), kTapFracBits), win, e_re, e_im)
    DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_l), kTapFracBits), win, l_re, l_im)
    if constexpr (kT == 5) {
      DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_ve), kTapFracBits), win, ve_re, ve_im)
      DEEPNAV_TAP(_mm512_srli_epi16(_mm512_add_epi16(w, d_vl), kTapFracBits), win, vl_re, vl_im)
    }
#undef DEEPNAV_TAP
    pos += block_inc;
    if (pos >= run.wrap) pos -= run.wrap;
  }
  // A run adds at most 128 * 2 * 2^15 per lane: int32 lanes and their sum cannot overflow.
#define DEEPNAV_ADD(T, RE, IM)              \
  acc[T][0] += _mm512_reduce_add_epi32(RE); \
  acc[T][1] += _mm512_reduce_add_epi32(IM);
  DEEPNAV_ADD(0, e_re, e_im)
  DEEPNAV_ADD(1, p_re, p_im)
  DEEPNAV_ADD(2, l_re, l_im)
  if constexpr (kT == 5) {
    DEEPNAV_ADD(3, ve_re, ve_im)
    DEEPNAV_ADD(4, vl_re, vl_im)
  }
  if constexpr (kN) {
    DEEPNAV_ADD(kNoise, n_re, n_im)
  }
#undef DEEPNAV_ADD
}

template <int kT, bool kSmall, bool kPlanar>
KernelFn with_noise(bool noise) {
  return noise ? kernel<kT, kSmall, kPlanar, true> : kernel<kT, kSmall, kPlanar, false>;
}

template <int kT>
KernelFn with_taps(bool small, bool planar, bool noise) {
  if (planar) return small ? with_noise<kT, true, true>(noise) : with_noise<kT, false, true>(noise);
  return small ? with_noise<kT, true, false>(noise) : with_noise<kT, false, false>(noise);
}

}  // namespace

KernelFn avx512_kernel(int taps, bool small, bool planar, bool noise) {
  return taps == 3 ? with_taps<3>(small, planar, noise) : with_taps<5>(small, planar, noise);
}

int sample_bits_avx512(const Sample* x, int n) { return sample_bits_impl(x, n); }

int deinterleave_avx512(const Sample* x, int n, std::int16_t* i, std::int16_t* q) {
  const auto* src = reinterpret_cast<const std::int32_t*>(x);
  const __m512i even = _mm512_load_si512(kEvenWords.w);
  const __m512i odd = _mm512_add_epi16(even, _mm512_set1_epi16(1));
  int k = 0;
  for (; k + 32 <= n; k += 32) {
    const __m512i x0 = _mm512_loadu_si512(src + k), x1 = _mm512_loadu_si512(src + k + 16);
    _mm512_storeu_si512(i + k, _mm512_permutex2var_epi16(x0, even, x1));
    _mm512_storeu_si512(q + k, _mm512_permutex2var_epi16(x0, odd, x1));
  }
  return k;
}

}  // namespace deepnav::correlator_detail
#endif
