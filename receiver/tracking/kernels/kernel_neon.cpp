// NEON kernel (AArch64 Advanced SIMD, part of every AArch64 CPU): 8 samples per iteration,
// the same integers as the portable kernel.
//
// The samples are deinterleaved by the load (vld2q); the carrier replica comes from the
// 32-entry int16 tables by byte lookup (vqtbl4q); the products follow the portable kernel
// (small inputs: exact int16 products; larger: vqrdmulh, which is pmulhrsw's rounding, and
// cannot saturate as no table entry is -32768); code levels come from a 16-chip window per
// block of samples by byte lookup; the taps multiply-accumulate pairwise into int32 lanes
// (a run of 4096 samples adds at most 2^25 per lane).
#include "receiver/tracking/kernels/kernels.hpp"

#if defined(__aarch64__)
#include <arm_neon.h>

namespace deepnav::correlator_detail {
namespace {

struct Lanes {  // accumulators of one tap
  int32x4_t re, im;
};

inline void tap(Lanes& a, int16x8_t re, int16x8_t im, int16x8_t level) {
  a.re = vpadalq_s16(a.re, vmulq_s16(re, level));
  a.im = vpadalq_s16(a.im, vmulq_s16(im, level));
}

/// Levels (+-1) of the window's chips at the positions w + d (2^-11 chip, relative to the window).
inline int16x8_t levels(int8x16_t win, uint16x8_t w, int16_t d) {
  const uint16x8_t chip = vshrq_n_u16(vaddq_u16(w, vdupq_n_u16(static_cast<std::uint16_t>(d))), kTapFracBits);
  return vmovl_s8(vqtbl1_s8(win, vmovn_u16(chip)));
}

inline void drain(const Lanes& a, std::int64_t* out) {
  out[0] += vaddlvq_s32(a.re);
  out[1] += vaddlvq_s32(a.im);
}

template <int kT, bool kSmall, bool kN>
void kernel(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
  const auto* src = reinterpret_cast<const std::int16_t*>(in.x);
  // The 32-entry tables as 64 bytes each, looked up with byte indices 2p, 2p + 1.
  const uint8x16x4_t cos_t = vld1q_u8_x4(reinterpret_cast<const std::uint8_t*>(su.cos_tab));
  const uint8x16x4_t sin_t = vld1q_u8_x4(reinterpret_cast<const std::uint8_t*>(su.sin_tab));
  const uint32x4_t lane = {0, 1, 2, 3};

  const uint32x4_t dphi = vdupq_n_u32(run.dphi);
  uint32x4_t phi_a = vmlaq_u32(vdupq_n_u32(run.phi0), lane, dphi);
  uint32x4_t phi_b = vaddq_u32(phi_a, vshlq_n_u32(dphi, 2));
  const uint32x4_t phi_step = vshlq_n_u32(dphi, 3);

  // Code positions of samples 0-3 and 4-7 relative to the block's first chip minus h.
  const uint32x4_t inc_v = vdupq_n_u32(static_cast<std::uint32_t>(run.inc));
  const uint32x4_t off_a = vmlaq_u32(vdupq_n_u32(static_cast<std::uint32_t>(su.h) << kCodeFracBits), lane, inc_v);
  const uint32x4_t off_b = vaddq_u32(off_a, vshlq_n_u32(inc_v, 2));

  Lanes sums[kTaps];
  for (Lanes& s : sums) s = {vdupq_n_s32(0), vdupq_n_s32(0)};

  std::int64_t pos = run.pos0;
  const std::int64_t block_inc = run.inc * 8;
  alignas(16) std::int16_t tail[16] = {};
  for (int k = 0; k < m; k += 8) {
    const std::int16_t* p = src + 2 * k;
    if (m - k < 8) {  // the missing samples are zero and add nothing
      for (int j = 0; j < 2 * (m - k); ++j) tail[j] = p[j];
      p = tail;
    }
    const int16x8x2_t x = vld2q_s16(p);
    const int16x8_t i = x.val[0], q = x.val[1];

    // Table index (bits 16-20 of the phase) as the byte offsets 2p (low byte), 2p + 1 (high).
    const uint16x8_t idx = vandq_u16(vcombine_u16(vshrn_n_u32(phi_a, 16), vshrn_n_u32(phi_b, 16)), vdupq_n_u16(31));
    phi_a = vaddq_u32(phi_a, phi_step);
    phi_b = vaddq_u32(phi_b, phi_step);
    const uint8x16_t bytes = vreinterpretq_u8_u16(vmlaq_n_u16(vdupq_n_u16(0x0100), idx, 0x0202));
    const int16x8_t c = vreinterpretq_s16_u8(vqtbl4q_u8(cos_t, bytes));
    const int16x8_t s = vreinterpretq_s16_u8(vqtbl4q_u8(sin_t, bytes));
    int16x8_t re, im;
    if constexpr (kSmall) {
      re = vmlaq_s16(vmulq_s16(i, c), q, s);
      im = vmlsq_s16(vmulq_s16(q, c), i, s);
    } else {
      re = vaddq_s16(vqrdmulhq_s16(i, c), vqrdmulhq_s16(q, s));
      im = vsubq_s16(vqrdmulhq_s16(q, c), vqrdmulhq_s16(i, s));
    }

    const auto first = static_cast<int>(pos >> kCodeFracBits);
    const uint32x4_t frac = vdupq_n_u32(static_cast<std::uint32_t>(pos & ((std::int64_t{1} << kCodeFracBits) - 1)));
    const uint16x8_t w = vcombine_u16(vshrn_n_u32(vaddq_u32(frac, off_a), 16), vshrn_n_u32(vaddq_u32(frac, off_b), 16));
    const int8x16_t win = vld1q_s8(su.code8 + first - su.h);
    const int16x8_t lp = levels(win, w, 0);
    tap(sums[1], re, im, lp);
    tap(sums[0], re, im, levels(win, w, su.d[0]));
    tap(sums[2], re, im, levels(win, w, su.d[2]));
    if constexpr (kT == 5) {
      tap(sums[3], re, im, levels(win, w, su.d[3]));
      tap(sums[4], re, im, levels(win, w, su.d[4]));
    }
    if constexpr (kN) tap(sums[kNoise], re, im, levels(vld1q_s8(su.noise8 + first - su.h), w, 0));
    pos += block_inc;
    if (pos >= run.wrap) pos -= run.wrap;
  }
  for (int t = 0; t < kTaps; ++t) drain(sums[t], acc[t]);
}

template <int kT, bool kSmall>
KernelFn with_noise(bool noise) {
  return noise ? kernel<kT, kSmall, true> : kernel<kT, kSmall, false>;
}

}  // namespace

KernelFn neon_kernel(int taps, bool small, bool noise) {
  if (taps == 3) return small ? with_noise<3, true>(noise) : with_noise<3, false>(noise);
  return small ? with_noise<5, true>(noise) : with_noise<5, false>(noise);
}

int sample_bits_neon(const Sample* x, int n) {
  const auto* p = reinterpret_cast<const std::int16_t*>(x);
  uint16x8_t acc = vdupq_n_u16(0);
  int k = 0;
  for (; k + 4 <= n; k += 4) acc = vorrq_u16(acc, vreinterpretq_u16_s16(vabsq_s16(vld1q_s16(p + 2 * k))));
  unsigned m = vmaxvq_u16(acc);  // the OR of the lanes has the same bit width as their maximum
  unsigned rest = 0;
  for (; k < n; ++k) {
    const int i = p[2 * k], q = p[2 * k + 1];
    rest |= static_cast<unsigned>(i < 0 ? -i : i) | static_cast<unsigned>(q < 0 ? -q : q);
  }
  m |= rest;
  int b = 0;
  while (m >> b) ++b;
  return b;
}

}  // namespace deepnav::correlator_detail
#endif
