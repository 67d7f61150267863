#include "receiver/correlator.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#if defined(__x86_64__)
// GCC 12 reports the deliberately undefined lanes of some AVX-512 intrinsics as
// maybe-uninitialized; the diagnostic points into the header, so it is silenced there only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif

namespace deepnav {
namespace {

constexpr int kLanes = 16;
constexpr int kRun = 1024;                // samples per run: phases restart exactly at each run
constexpr int kFracBits = 21;             // code index: 11 integer bits (< 2048 chips), 21 fraction bits
constexpr double kFracOne = 2097152.0;    // 2^21
constexpr int kTableChips = 2048;         // code levels over two periods and a bit: no wrap inside a run
constexpr double kPeriodChips = 1023.0;

#define DEEPNAV_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))

/// Carrier wipe-off of n <= kRun samples: (re, im) = x * conj(replica). The replica phasor
/// of lane l starts at (cr[l], ci[l]) and advances by w every kLanes samples.
DEEPNAV_SIMD_CLONES
void wipe_carrier(const std::int16_t* __restrict iq, int n, float* __restrict re_out, float* __restrict im_out,
                  float* __restrict cr, float* __restrict ci, float wr, float wi) {
  int k = 0;
  for (; k + kLanes <= n; k += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const float xi = iq[2 * (k + l)], xq = iq[2 * (k + l) + 1];
      // x * conj(c) = (xi cr + xq ci) + j (xq cr - xi ci)
      re_out[k + l] = xi * cr[l] + xq * ci[l];
      im_out[k + l] = xq * cr[l] - xi * ci[l];
      const float nr = cr[l] * wr - ci[l] * wi;
      const float ni = cr[l] * wi + ci[l] * wr;
      cr[l] = nr;
      ci[l] = ni;
    }
  }
  for (int l = 0; k < n; ++k, ++l) {
    const float xi = iq[2 * k], xq = iq[2 * k + 1];
    re_out[k] = xi * cr[l] + xq * ci[l];
    im_out[k] = xq * cr[l] - xi * ci[l];
  }
}

/// Code wipe-off and accumulation for T taps that share one code table, each starting at
/// its own fixed-point index and advancing by `inc` per sample. Portable version: partial
/// sums are kept per lane so the reduction vectorises without reassociation flags.
template <int T>
[[gnu::always_inline]] inline void tap_sums_portable(const float* __restrict re, const float* __restrict im, int n,
                                                     const std::uint32_t* start, std::uint32_t inc,
                                                     const float* __restrict table, float* out_re, float* out_im) {
  float ar[T][kLanes] = {}, ai[T][kLanes] = {};
  int k = 0;
  for (; k + kLanes <= n; k += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const std::uint32_t offset = static_cast<std::uint32_t>(k + l) * inc;
      for (int t = 0; t < T; ++t) {
        const float c = table[(start[t] + offset) >> kFracBits];
        ar[t][l] += re[k + l] * c;
        ai[t][l] += im[k + l] * c;
      }
    }
  }
  for (int l = 0; k < n; ++k, ++l) {
    const std::uint32_t offset = static_cast<std::uint32_t>(k) * inc;
    for (int t = 0; t < T; ++t) {
      const float c = table[(start[t] + offset) >> kFracBits];
      ar[t][l] += re[k] * c;
      ai[t][l] += im[k] * c;
    }
  }
  for (int t = 0; t < T; ++t) {
    float sr = 0.0f, si = 0.0f;
    for (int l = 0; l < kLanes; ++l) {
      sr += ar[t][l];
      si += ai[t][l];
    }
    out_re[t] = sr;
    out_im[t] = si;
  }
}

/// Scalar tail of the intrinsic kernels (the last n % lanes samples of a run).
template <int T>
[[gnu::always_inline]] inline void tap_tail(const float* re, const float* im, int k, int n, const std::uint32_t* start,
                                            std::uint32_t inc, const float* table, float* out_re, float* out_im) {
  for (; k < n; ++k) {
    const std::uint32_t offset = static_cast<std::uint32_t>(k) * inc;
    for (int t = 0; t < T; ++t) {
      const float c = table[(start[t] + offset) >> kFracBits];
      out_re[t] += re[k] * c;
      out_im[t] += im[k] * c;
    }
  }
}

#if defined(__x86_64__)
/// AVX-512: 16 samples of a tap span at most 16 step + 1 chips. With step below 14/15 chip
/// they fit in one unaligned 16-entry load of the table, and a lane permutation replaces
/// the gather; faster steps fall back to the gather.
template <int T, bool kPermute>
__attribute__((target("avx512f"), always_inline)) inline void tap_sums_avx512(
    const float* re, const float* im, int n, const std::uint32_t* start, std::uint32_t inc, const float* table,
    float* out_re, float* out_im) {
  const __m512i lane_offset = _mm512_mullo_epi32(
      _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15), _mm512_set1_epi32(static_cast<int>(inc)));
  __m512 acc_re[T], acc_im[T];
  for (int t = 0; t < T; ++t) acc_re[t] = acc_im[t] = _mm512_setzero_ps();
  int k = 0;
  for (; k + 16 <= n; k += 16) {
    const __m512 x_re = _mm512_loadu_ps(re + k), x_im = _mm512_loadu_ps(im + k);
    const std::uint32_t k_offset = static_cast<std::uint32_t>(k) * inc;
    for (int t = 0; t < T; ++t) {
      const std::uint32_t base = start[t] + k_offset;
      const __m512i fixed = _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(base)), lane_offset);
      const __m512i chip = _mm512_srli_epi32(fixed, kFracBits);
      __m512 c;
      if constexpr (kPermute) {
        const int first = static_cast<int>(base >> kFracBits);
        c = _mm512_permutexvar_ps(_mm512_sub_epi32(chip, _mm512_set1_epi32(first)), _mm512_loadu_ps(table + first));
      } else {
        c = _mm512_i32gather_ps(chip, table, 4);
      }
      acc_re[t] = _mm512_fmadd_ps(x_re, c, acc_re[t]);
      acc_im[t] = _mm512_fmadd_ps(x_im, c, acc_im[t]);
    }
  }
  for (int t = 0; t < T; ++t) {
    out_re[t] = _mm512_reduce_add_ps(acc_re[t]);
    out_im[t] = _mm512_reduce_add_ps(acc_im[t]);
  }
  tap_tail<T>(re, im, k, n, start, inc, table, out_re, out_im);
}

/// AVX2: the same with 8 lanes (permutation while 8 samples span at most 8 chips).
template <int T, bool kPermute>
__attribute__((target("avx2,fma"), always_inline)) inline void tap_sums_avx2(
    const float* re, const float* im, int n, const std::uint32_t* start, std::uint32_t inc, const float* table,
    float* out_re, float* out_im) {
  const __m256i lane_offset =
      _mm256_mullo_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32(static_cast<int>(inc)));
  __m256 acc_re[T], acc_im[T];
  for (int t = 0; t < T; ++t) acc_re[t] = acc_im[t] = _mm256_setzero_ps();
  int k = 0;
  for (; k + 8 <= n; k += 8) {
    const __m256 x_re = _mm256_loadu_ps(re + k), x_im = _mm256_loadu_ps(im + k);
    const std::uint32_t k_offset = static_cast<std::uint32_t>(k) * inc;
    for (int t = 0; t < T; ++t) {
      const std::uint32_t base = start[t] + k_offset;
      const __m256i fixed = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(base)), lane_offset);
      const __m256i chip = _mm256_srli_epi32(fixed, kFracBits);
      __m256 c;
      if constexpr (kPermute) {
        const int first = static_cast<int>(base >> kFracBits);
        c = _mm256_permutevar8x32_ps(_mm256_loadu_ps(table + first), _mm256_sub_epi32(chip, _mm256_set1_epi32(first)));
      } else {
        c = _mm256_i32gather_ps(table, chip, 4);
      }
      acc_re[t] = _mm256_fmadd_ps(x_re, c, acc_re[t]);
      acc_im[t] = _mm256_fmadd_ps(x_im, c, acc_im[t]);
    }
  }
  for (int t = 0; t < T; ++t) {
    alignas(32) float r[8], i[8];
    _mm256_store_ps(r, acc_re[t]);
    _mm256_store_ps(i, acc_im[t]);
    out_re[t] = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
    out_im[t] = ((i[0] + i[1]) + (i[2] + i[3])) + ((i[4] + i[5]) + (i[6] + i[7]));
  }
  tap_tail<T>(re, im, k, n, start, inc, table, out_re, out_im);
}
#endif

/// One kernel per instruction set and tap count (T taps share one code table).
template <int T>
void tap_sums(CorrelatorKernel kernel, const float* re, const float* im, int n, const std::uint32_t* start,
              std::uint32_t inc, const float* table, float* out_re, float* out_im);

#if defined(__x86_64__)
template <int T>
__attribute__((target("avx512f"))) void tap_sums_avx512_dispatch(const float* re, const float* im, int n,
                                                                  const std::uint32_t* start, std::uint32_t inc,
                                                                  const float* table, float* out_re, float* out_im) {
  if (static_cast<double>(inc) * 15.0 < 14.0 * kFracOne)
    tap_sums_avx512<T, true>(re, im, n, start, inc, table, out_re, out_im);
  else
    tap_sums_avx512<T, false>(re, im, n, start, inc, table, out_re, out_im);
}

template <int T>
__attribute__((target("avx2,fma"))) void tap_sums_avx2_dispatch(const float* re, const float* im, int n,
                                                                 const std::uint32_t* start, std::uint32_t inc,
                                                                 const float* table, float* out_re, float* out_im) {
  if (static_cast<double>(inc) * 7.0 < 6.0 * kFracOne)
    tap_sums_avx2<T, true>(re, im, n, start, inc, table, out_re, out_im);
  else
    tap_sums_avx2<T, false>(re, im, n, start, inc, table, out_re, out_im);
}
#endif

template <int T>
void tap_sums_portable_call(const float* re, const float* im, int n, const std::uint32_t* start, std::uint32_t inc,
                            const float* table, float* out_re, float* out_im) {
  tap_sums_portable<T>(re, im, n, start, inc, table, out_re, out_im);
}

template <int T>
void tap_sums(CorrelatorKernel kernel, const float* re, const float* im, int n, const std::uint32_t* start,
              std::uint32_t inc, const float* table, float* out_re, float* out_im) {
  switch (kernel) {
#if defined(__x86_64__)
    case CorrelatorKernel::avx512:
      tap_sums_avx512_dispatch<T>(re, im, n, start, inc, table, out_re, out_im);
      return;
    case CorrelatorKernel::avx2:
      tap_sums_avx2_dispatch<T>(re, im, n, start, inc, table, out_re, out_im);
      return;
#endif
    default:
      tap_sums_portable_call<T>(re, im, n, start, inc, table, out_re, out_im);
  }
}

/// Code levels as floats over kTableChips chips (chip c holds code[c mod 1023]).
struct CodeTable {
  alignas(64) float levels[kTableChips + 16];  // + 16: a permuting kernel loads 16 past its first chip
  explicit CodeTable(const CaCodeChips& code) {
    for (int c = 0; c < kTableChips + 16; ++c) levels[c] = static_cast<float>(code[static_cast<std::size_t>(c % 1023)]);
  }
};

/// The table of a code, rebuilt only when the caller switches codes (a channel keeps its own
/// two codes, so per thread this is a cache hit except when channels interleave).
const float* table_for(const CaCodeChips& code, int slot) {
  thread_local const CaCodeChips* cached[2] = {nullptr, nullptr};
  thread_local std::unique_ptr<CodeTable> tables[2];
  if (cached[slot] != &code) {
    tables[slot] = std::make_unique<CodeTable>(code);
    cached[slot] = &code;
  }
  return tables[slot]->levels;
}

double wrap_chips(double chips) {
  double c = std::fmod(chips, kPeriodChips);
  if (c < 0.0) c += kPeriodChips;
  return c;
}

std::uint32_t fixed_index(double chips) { return static_cast<std::uint32_t>(wrap_chips(chips) * kFracOne); }

}  // namespace

std::vector<CorrelatorKernel> available_correlator_kernels() {
  std::vector<CorrelatorKernel> k{CorrelatorKernel::portable};
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) k.push_back(CorrelatorKernel::avx2);
  if (__builtin_cpu_supports("avx512f")) k.push_back(CorrelatorKernel::avx512);
#endif
  return k;
}

CorrelatorKernel best_correlator_kernel() {
  static const CorrelatorKernel best = available_correlator_kernels().back();
  return best;
}

CorrelatorSums correlate(const Sample* samples, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                         const CaCodeChips& noise_code) {
  return correlate(best_correlator_kernel(), samples, n, s, code, noise_code);
}

CorrelatorSums correlate(CorrelatorKernel kernel, const Sample* samples, int n, const CorrelatorSpan& s,
                         const CaCodeChips& code, const CaCodeChips& noise_code) {
  CorrelatorSums out;
  if (n <= 0) return out;
  if (!(s.code_step_chips > 0.0 && s.code_step_chips <= 2.0))
    throw std::invalid_argument("correlate: code step per sample must be in (0, 2] chips, got " +
                                std::to_string(s.code_step_chips));
  const float* table = table_for(code, 0);
  const float* noise_table = table_for(noise_code, 1);
  const bool very = s.very_spacing_chips > 0.0;
  // A run must keep every index below kTableChips: start < 1023, plus run * step.
  const int run_max = std::min(kRun, static_cast<int>((kTableChips - kPeriodChips - 2.0) / s.code_step_chips));
  const auto inc = static_cast<std::uint32_t>(std::llround(s.code_step_chips * kFracOne));
  constexpr double kTwoPi = 2.0 * M_PI;
  const std::complex<double> lane_step = std::polar(1.0, kTwoPi * s.carrier_step_cycles);
  const std::complex<double> w = std::polar(1.0, kTwoPi * kLanes * s.carrier_step_cycles);
  const double half = 0.5 * s.spacing_chips, very_half = 0.5 * s.very_spacing_chips;

  alignas(64) float re[kRun], im[kRun];
  alignas(64) float cr[kLanes], ci[kLanes];
  const auto* iq = reinterpret_cast<const std::int16_t*>(samples);
  for (int k0 = 0; k0 < n; k0 += run_max) {
    const int m = std::min(run_max, n - k0);
    // Exact phases at the run start: the float recursions never run longer than one run.
    const double carrier = s.carrier_phase_cycles + k0 * s.carrier_step_cycles;
    std::complex<double> z = std::polar(1.0, kTwoPi * (carrier - std::floor(carrier)));
    for (int l = 0; l < kLanes; ++l, z *= lane_step) {
      cr[l] = static_cast<float>(z.real());
      ci[l] = static_cast<float>(z.imag());
    }
    wipe_carrier(iq + 2 * static_cast<std::ptrdiff_t>(k0), m, re, im, cr, ci, static_cast<float>(w.real()),
                 static_cast<float>(w.imag()));

    const double prompt = s.code_phase_chips + k0 * s.code_step_chips;
    float sr[3], si[3];
    const std::uint32_t epl[3] = {fixed_index(prompt + half), fixed_index(prompt), fixed_index(prompt - half)};
    tap_sums<3>(kernel, re, im, m, epl, inc, table, sr, si);
    out.early += std::complex<double>(sr[0], si[0]);
    out.prompt += std::complex<double>(sr[1], si[1]);
    out.late += std::complex<double>(sr[2], si[2]);
    if (very) {
      const std::uint32_t vel[2] = {fixed_index(prompt + very_half), fixed_index(prompt - very_half)};
      tap_sums<2>(kernel, re, im, m, vel, inc, table, sr, si);
      out.very_early += std::complex<double>(sr[0], si[0]);
      out.very_late += std::complex<double>(sr[1], si[1]);
    }
    const std::uint32_t noise_start[1] = {epl[1]};
    tap_sums<1>(kernel, re, im, m, noise_start, inc, noise_table, sr, si);
    out.noise += std::complex<double>(sr[0], si[0]);
  }
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
