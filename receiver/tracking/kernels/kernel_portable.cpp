// Portable kernel: the definition of the integers every kernel computes, sample by sample.
#include <cstdlib>

#include "receiver/tracking/kernels/kernels.hpp"

namespace deepnav::correlator_detail {
namespace {

inline std::int16_t mulhrs(std::int16_t a, std::int16_t b) {
  return static_cast<std::int16_t>((static_cast<std::int32_t>(a) * b + 0x4000) >> 15);
}

inline std::int16_t level(const std::int16_t* table, std::int64_t chip, int period) {
  if (chip >= -kPad && chip < period + kPad) return table[chip];
  return table[((chip % period) + period) % period];
}

template <bool kSmall, int kT, bool kNear, bool kN>
void kernel_impl(const Input& in, int m, const Run& run, const Setup& su, Acc& acc) {
  const auto* x = reinterpret_cast<const std::int16_t*>(in.x);
  // kNear: every tap within kPad chips, so a chip index never leaves the padded table.
  const auto chip_level = [&su](const std::int16_t* table, std::int64_t chip) {
    return kNear ? table[chip] : level(table, chip, su.period);
  };
  std::int64_t offset[kT];
  for (int t = 0; t < kT; ++t) offset[t] = std::int64_t{su.d[t]} << (kCodeFracBits - kTapFracBits);
  std::int32_t sums[kTaps][2] = {};  // a run adds at most 4096 * 2^15 < 2^31
  std::int64_t pos = run.pos0;
  std::uint32_t phi = run.phi0;
  for (int k = 0; k < m; ++k, phi += run.dphi) {
    const unsigned p = (phi >> 16) & 31u;
    const std::int16_t c = su.cos_tab[p], s = su.sin_tab[p];
    const std::int16_t i = x[2 * k], q = x[2 * k + 1];
    std::int32_t re, im;
    if constexpr (kSmall) {  // |i|, |q| <= 127, |c|, |s| <= 126: exact, within int16
      re = i * c + q * s;
      im = q * c - i * s;
    } else {
      re = static_cast<std::int16_t>(mulhrs(i, c) + mulhrs(q, s));
      im = static_cast<std::int16_t>(mulhrs(q, c) - mulhrs(i, s));
    }
    for (int t = 0; t < kT; ++t) {
      const std::int16_t l = chip_level(su.code16, (pos + offset[t]) >> kCodeFracBits);
      sums[t][0] += re * l;
      sums[t][1] += im * l;
    }
    if constexpr (kN) {
      const std::int16_t l = chip_level(su.noise16, pos >> kCodeFracBits);
      sums[kNoise][0] += re * l;
      sums[kNoise][1] += im * l;
    }
    pos += run.inc;
    if (pos >= run.wrap) pos -= run.wrap;
  }
  for (int t = 0; t < kTaps; ++t) {
    acc[t][0] += sums[t][0];
    acc[t][1] += sums[t][1];
  }
}

template <bool kSmall, bool kN>
void kernel(const Input& x, int m, const Run& run, const Setup& su, Acc& acc) {
  const bool near = su.h <= kPad;
  if (su.taps == 3) (near ? kernel_impl<kSmall, 3, true, kN> : kernel_impl<kSmall, 3, false, kN>)(x, m, run, su, acc);
  else (near ? kernel_impl<kSmall, 5, true, kN> : kernel_impl<kSmall, 5, false, kN>)(x, m, run, su, acc);
}

template <bool kSmall>
void dispatch(const Input& x, int m, const Run& run, const Setup& su, Acc& acc) {
  (su.noise ? kernel<kSmall, true> : kernel<kSmall, false>)(x, m, run, su, acc);
}

}  // namespace

KernelFn portable_kernel(bool small) { return small ? dispatch<true> : dispatch<false>; }

int sample_bits_portable(const Sample* x, int n) {
  unsigned m = 0;
  const auto* iq = reinterpret_cast<const std::int16_t*>(x);
  for (int k = 0; k < 2 * n; ++k) m |= static_cast<unsigned>(std::abs(static_cast<int>(iq[k])));
  int b = 0;
  while (m >> b) ++b;
  return b;
}

}  // namespace deepnav::correlator_detail
