// AVX2 kernels, compiled with -mavx2 (receiver/CMakeLists.txt); called only on CPUs with AVX2.
// Inputs of at most 7 bits (|I|, |Q| <= 127, every 1- to 8-bit converter) take an int8
// pipeline; larger ones the int16 pipeline (kernel_wide).
#include "receiver/tracking/kernels/kernels.hpp"

#if defined(__x86_64__)
#include <immintrin.h>

namespace deepnav::correlator_detail {
namespace {

// ---------------------------------------------------------------------------------------
// AVX2: 16 samples per iteration. Word 2j of a register holds sample j, word 2j+1 sample
// 8 + j, so that 16-bit halves of two dword registers interleave with one blend.
int sample_bits_impl(const Sample* x, int n) {
  const auto* p = reinterpret_cast<const std::int32_t*>(x);
  __m256i acc0 = _mm256_setzero_si256(), acc1 = acc0;
  int k = 0;
  for (; k + 32 <= n; k += 32) {
    const auto* v = reinterpret_cast<const __m256i*>(p + k);
    acc0 = _mm256_or_si256(
        acc0, _mm256_or_si256(_mm256_abs_epi16(_mm256_loadu_si256(v)), _mm256_abs_epi16(_mm256_loadu_si256(v + 1))));
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
  int b = 0;
  while (m >> b) ++b;
  return b;
}

/// Adds the int32 lanes of v / 256 to out and clears v (the lanes hold multiples of 256).
/// Adds the int32 lanes of v to the four int64 lanes of `wide` and clears v.
inline void drain(__m256i& v, __m256i& wide) {
  const __m256i lo = _mm256_cvtepi32_epi64(_mm256_castsi256_si128(v));
  const __m256i hi = _mm256_cvtepi32_epi64(_mm256_extracti128_si256(v, 1));
  wide = _mm256_add_epi64(wide, _mm256_add_epi64(lo, hi));
  v = _mm256_setzero_si256();
}

/// Adds the drained sums / 256 to acc (every lane holds a multiple of 256).
inline void finish(__m256i (&wide)[kTaps][2], Acc& acc) {
  for (int t = 0; t < kTaps; ++t) {
    for (int c = 0; c < 2; ++c) {
      alignas(32) std::int64_t lanes[4];
      _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), wide[t][c]);
      acc[t][c] += (lanes[0] + lanes[1] + lanes[2] + lanes[3]) / 256;
    }
  }
}

template <int kT, bool kSmall, bool kN>
void kernel_wide(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
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

  __m256i wide[kTaps][2];
  for (auto& t : wide) t[0] = t[1] = _mm256_setzero_si256();
  std::int64_t pos = run.pos0;
  const std::int64_t block_inc = run.inc * 16;
  // Two passes per chunk of 64 blocks, so that neither needs more than the 16 registers:
  // carrier wipe-off into re/im buffers, then the taps.
  alignas(32) std::int16_t re_buf[64 * 16], im_buf[64 * 16];
  for (int k0 = 0; k0 < m; k0 += 64 * 16) {
    const int k_end = m < k0 + 64 * 16 ? m : k0 + 64 * 16;
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
          kN ? _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(su.noise8 + first - su.h)))
             : win;
      // Index words: high byte the chip (position >> 11), low byte 0x80 so that pshufb puts
      // the level (+-1) in the high byte: code words of +-256.
#define DEEPNAV_IDX(D) _mm256_or_si256(_mm256_srli_epi16(D, kTapFracBits - 8), zero_low)
#define DEEPNAV_TAP(IDX, WIN, RE, IM)                       \
  {                                                         \
    const __m256i code = _mm256_shuffle_epi8(WIN, IDX);     \
    RE = _mm256_add_epi32(RE, _mm256_madd_epi16(re, code)); \
    IM = _mm256_add_epi32(IM, _mm256_madd_epi16(im, code)); \
  }
      const __m256i idx_p = DEEPNAV_IDX(w);
      DEEPNAV_TAP(idx_p, win, p_re, p_im)
      if constexpr (kN) DEEPNAV_TAP(idx_p, nwin, n_re, n_im)  // the noise tap shares the prompt's timing
      DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_e)), win, e_re, e_im)
      DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_l)), win, l_re, l_im)
      if constexpr (kT == 5) {
        DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_ve)), win, ve_re, ve_im)
        DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_vl)), win, vl_re, vl_im)
      }
#undef DEEPNAV_TAP
#undef DEEPNAV_IDX
      pos += block_inc;
      if (pos >= run.wrap) pos -= run.wrap;
    }
    // Each madd adds up to 2^24 per lane: 64 iterations stay within int32.
    drain(e_re, wide[0][0]);
    drain(e_im, wide[0][1]);
    drain(p_re, wide[1][0]);
    drain(p_im, wide[1][1]);
    drain(l_re, wide[2][0]);
    drain(l_im, wide[2][1]);
    if constexpr (kT == 5) {
      drain(ve_re, wide[3][0]);
      drain(ve_im, wide[3][1]);
      drain(vl_re, wide[4][0]);
      drain(vl_im, wide[4][1]);
    }
    if constexpr (kN) {
      drain(n_re, wide[kNoise][0]);
      drain(n_im, wide[kNoise][1]);
    }
  }
  finish(wide, acc);
}

// ---------------------------------------------------------------------------------------
// int8 pipeline, 16 samples per iteration. The samples are packed to bytes (I, Q of a
// sample side by side), the carrier replica is built as bytes, and one vpmaddubsw per
// component gives the wiped-off sample as int16: re = I c + Q s, im = I (-s) + Q c (the
// products are exact: |I|, |Q| <= 127, |c|, |s| <= 126, so a pair sum stays below 32004).
// vpmaddubsw wants one operand unsigned: it gets |I|, |Q|, and the replica takes the
// samples' signs (vpsignb).
//
// The packing puts samples 0-3, 8-11 in the low lane and 4-7, 12-15 in the high lane; the
// carrier phases and code positions (two dword registers: samples 0-7 and 8-15) are packed
// to words with the same instruction, so they come out in the same order.
//
// Replica bytes from one 16-entry table: sin(p) = cos(p - 8), -sin(p) = cos(p + 8) and
// cos(p + 16) = -cos(p) for the 32-bin table (bins centred on (p + 1/2) 2 pi / 32), so a byte
// index j = p + {0, 8, 24} looks up |j mod 16| and bit 4 of j is the sign, which is moved onto
// the sample byte (flipping its sign bit flips the sign vpsignb gives; a zero sample adds
// nothing either way).
template <int kT, bool kN>
void kernel_int8(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
  const auto* src = reinterpret_cast<const std::int32_t*>(in.x);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i eight = _mm256_set1_epi32(8);
  const __m256i tab =
      _mm256_broadcastsi128_si256(_mm_packs_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(su.cos_tab)),
                                                  _mm_loadu_si128(reinterpret_cast<const __m128i*>(su.cos_tab + 8))));
  const __m256i k_re = _mm256_set1_epi16(0x1800);  // bytes: p (cos), p + 24 (sin)
  const __m256i k_im = _mm256_set1_epi16(0x0008);  // bytes: p + 8 (-sin), p (cos)
  const __m256i sign_bits = _mm256_set1_epi16(static_cast<short>(0x8080));
  const __m256i dup = _mm256_set1_epi16(0x0101);

  // Carrier phases shifted up by 11 bits: the table index (bits 16-20) is the top 5 bits.
  const __m256i dphi = _mm256_set1_epi32(static_cast<int>(run.dphi << 11));
  __m256i phi_a = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(run.phi0 << 11)), _mm256_mullo_epi32(lane, dphi));
  __m256i phi_b = _mm256_add_epi32(phi_a, _mm256_mullo_epi32(eight, dphi));
  const __m256i phi_step = _mm256_slli_epi32(dphi, 4);

  // Code positions of samples 0-7 and 8-15 relative to the block's first chip minus h, 2^27
  // per chip; bits 16 and up are the position in 2^-11 chip (the tap offsets' unit).
  const auto inc = static_cast<std::uint32_t>(run.inc);
  const __m256i inc_v = _mm256_set1_epi32(static_cast<int>(inc));
  const __m256i off_a =
      _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(static_cast<std::uint32_t>(su.h) << kCodeFracBits)),
                       _mm256_mullo_epi32(lane, inc_v));
  const __m256i off_b = _mm256_add_epi32(off_a, _mm256_mullo_epi32(eight, inc_v));
  const __m256i zero_low = _mm256_set1_epi16(0x0080);  // pshufb index with bit 7 set gives 0
  const __m256i d_e = _mm256_set1_epi16(su.d[0]), d_l = _mm256_set1_epi16(su.d[2]);
  const __m256i d_ve = _mm256_set1_epi16(su.d[3]), d_vl = _mm256_set1_epi16(su.d[4]);

  __m256i e_re = _mm256_setzero_si256(), e_im = e_re, p_re = e_re, p_im = e_re, l_re = e_re, l_im = e_re;
  __m256i ve_re = e_re, ve_im = e_re, vl_re = e_re, vl_im = e_re, n_re = e_re, n_im = e_re;

  __m256i wide[kTaps][2];
  for (auto& t : wide) t[0] = t[1] = _mm256_setzero_si256();
  std::int64_t pos = run.pos0;
  const std::int64_t block_inc = run.inc * 16;
  for (int k0 = 0; k0 < m; k0 += 64 * 16) {
    const int k_end = m < k0 + 64 * 16 ? m : k0 + 64 * 16;
    for (int k = k0; k < k_end; k += 16) {
      __m256i x0, x1;
      if (const int left = m - k; left >= 16) [[likely]] {
        x0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + k));
        x1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + k + 8));
      } else {  // masked loads: the missing samples are zero and add nothing
        x0 = _mm256_maskload_epi32(src + k, _mm256_cmpgt_epi32(_mm256_set1_epi32(left), lane));
        x1 = _mm256_maskload_epi32(src + k + 8, _mm256_cmpgt_epi32(_mm256_set1_epi32(left - 8), lane));
      }
      const __m256i x = _mm256_packs_epi16(x0, x1);
      const __m256i ax = _mm256_abs_epi8(x);

      const __m256i p = _mm256_packus_epi32(_mm256_srli_epi32(phi_a, 27), _mm256_srli_epi32(phi_b, 27));
      phi_a = _mm256_add_epi32(phi_a, phi_step);
      phi_b = _mm256_add_epi32(phi_b, phi_step);
      const __m256i pp = _mm256_mullo_epi16(p, dup);  // p in both bytes
      const __m256i j_re = _mm256_add_epi16(pp, k_re), j_im = _mm256_add_epi16(pp, k_im);
      const __m256i rep_re = _mm256_sign_epi8(
          _mm256_shuffle_epi8(tab, j_re), _mm256_xor_si256(x, _mm256_and_si256(_mm256_slli_epi16(j_re, 3), sign_bits)));
      const __m256i rep_im = _mm256_sign_epi8(
          _mm256_shuffle_epi8(tab, j_im), _mm256_xor_si256(x, _mm256_and_si256(_mm256_slli_epi16(j_im, 3), sign_bits)));
      const __m256i re = _mm256_maddubs_epi16(ax, rep_re);
      const __m256i im = _mm256_maddubs_epi16(ax, rep_im);

      const auto first = static_cast<int>(pos >> kCodeFracBits);
      const __m256i frac = _mm256_set1_epi32(static_cast<int>(pos & ((std::int64_t{1} << kCodeFracBits) - 1)));
      const __m256i w = _mm256_packus_epi32(_mm256_srli_epi32(_mm256_add_epi32(frac, off_a), 16),
                                            _mm256_srli_epi32(_mm256_add_epi32(frac, off_b), 16));
      const __m256i win =
          _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(su.code8 + first - su.h)));
      // Index words: high byte the chip (position >> 11), low byte 0x80 so that pshufb puts
      // the level (+-1) in the high byte: code words of +-256.
#define DEEPNAV_IDX(D) _mm256_or_si256(_mm256_srli_epi16(D, kTapFracBits - 8), zero_low)
#define DEEPNAV_TAP(IDX, WIN, RE, IM)                       \
  {                                                         \
    const __m256i code = _mm256_shuffle_epi8(WIN, IDX);     \
    RE = _mm256_add_epi32(RE, _mm256_madd_epi16(re, code)); \
    IM = _mm256_add_epi32(IM, _mm256_madd_epi16(im, code)); \
  }
      const __m256i idx_p = DEEPNAV_IDX(w);
      DEEPNAV_TAP(idx_p, win, p_re, p_im)
      if constexpr (kN) {  // the noise tap shares the prompt's timing
        const __m256i nwin =
            _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(su.noise8 + first - su.h)));
        DEEPNAV_TAP(idx_p, nwin, n_re, n_im)
      }
      DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_e)), win, e_re, e_im)
      DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_l)), win, l_re, l_im)
      if constexpr (kT == 5) {
        DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_ve)), win, ve_re, ve_im)
        DEEPNAV_TAP(DEEPNAV_IDX(_mm256_add_epi16(w, d_vl)), win, vl_re, vl_im)
      }
#undef DEEPNAV_TAP
#undef DEEPNAV_IDX
      pos += block_inc;
      if (pos >= run.wrap) pos -= run.wrap;
    }
    // Each madd adds below 2^24 per lane: 64 iterations stay within int32.
    drain(e_re, wide[0][0]);
    drain(e_im, wide[0][1]);
    drain(p_re, wide[1][0]);
    drain(p_im, wide[1][1]);
    drain(l_re, wide[2][0]);
    drain(l_im, wide[2][1]);
    if constexpr (kT == 5) {
      drain(ve_re, wide[3][0]);
      drain(ve_im, wide[3][1]);
      drain(vl_re, wide[4][0]);
      drain(vl_im, wide[4][1]);
    }
    if constexpr (kN) {
      drain(n_re, wide[kNoise][0]);
      drain(n_im, wide[kNoise][1]);
    }
  }
  finish(wide, acc);
}

template <int kT>
KernelFn pick(bool small, bool noise) {
  if (small) return noise ? kernel_int8<kT, true> : kernel_int8<kT, false>;
  return noise ? kernel_wide<kT, false, true> : kernel_wide<kT, false, false>;
}

}  // namespace

KernelFn avx2_kernel(int taps, bool small, bool noise) {
  return taps == 3 ? pick<3>(small, noise) : pick<5>(small, noise);
}

int sample_bits_avx2(const Sample* x, int n) { return sample_bits_impl(x, n); }

}  // namespace deepnav::correlator_detail
#endif
