#include "receiver/correlator.hpp"

#include <cmath>
#include <memory>
#include <vector>

namespace deepnav {
namespace {

constexpr int kLanes = 16;
#define DEEPNAV_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))

/// Carrier wipe-off: (i, q) = x * conj(replica carrier).
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

/// Sum of (re, im) times code levels at a fixed-point code index (no wrap inside: the
/// caller extends the code table by one period so indices up to 2046 are valid).
DEEPNAV_SIMD_CLONES
void code_sum(const float* __restrict re, const float* __restrict im, int n, std::uint64_t acc, std::uint64_t inc,
              const float* __restrict levels, float& sum_re, float& sum_im) {
  float sr = 0.0f, si = 0.0f;
  for (int k = 0; k < n; ++k) {
    const float c = levels[(acc + static_cast<std::uint64_t>(k) * inc) >> 32];
    sr += re[k] * c;
    si += im[k] * c;
  }
  sum_re = sr;
  sum_im = si;
}

/// Code levels over two periods (index 0..2045) so a span of at most one period never wraps.
struct TwoPeriodCode {
  float levels[2 * 1023];
  explicit TwoPeriodCode(const CaCodeChips& code) {
    for (int c = 0; c < 2 * 1023; ++c) levels[c] = static_cast<float>(code[static_cast<std::size_t>(c % 1023)]);
  }
};

std::complex<double> code_correlation(const float* re, const float* im, int n, double chip0, double step,
                                      const float* levels) {
  constexpr double kOne = 4294967296.0;
  chip0 = std::fmod(chip0, 1023.0);
  if (chip0 < 0.0) chip0 += 1023.0;
  // Spans longer than about one period are split so the index stays inside the table.
  const int max_run = static_cast<int>(std::floor(1022.0 / std::max(step, 1e-9)));
  std::complex<double> total = 0.0;
  int k = 0;
  while (k < n) {
    const int run = std::min(n - k, std::max(1, max_run));
    float sr = 0.0f, si = 0.0f;
    code_sum(re + k, im + k, run, static_cast<std::uint64_t>(chip0 * kOne), static_cast<std::uint64_t>(step * kOne + 0.5),
             levels, sr, si);
    total += std::complex<double>(sr, si);
    chip0 = std::fmod(chip0 + run * step, 1023.0);
    k += run;
  }
  return total;
}

}  // namespace

CorrelatorSums correlate(const Sample* samples, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                         const CaCodeChips& noise_code) {
  CorrelatorSums out;
  if (n <= 0) return out;
  thread_local std::vector<float> re, im;
  re.resize(static_cast<std::size_t>(n));
  im.resize(static_cast<std::size_t>(n));
  // Replica carrier phasors for the 16 lanes, from exact exponentials.
  alignas(64) float cr[kLanes], ci[kLanes];
  const double two_pi = 2.0 * M_PI;
  const std::complex<double> step = std::polar(1.0, two_pi * s.carrier_step_cycles);
  std::complex<double> z = std::polar(1.0, two_pi * (s.carrier_phase_cycles - std::floor(s.carrier_phase_cycles)));
  for (int l = 0; l < kLanes; ++l, z *= step) {
    cr[l] = static_cast<float>(z.real());
    ci[l] = static_cast<float>(z.imag());
  }
  const std::complex<double> w = std::polar(1.0, two_pi * kLanes * s.carrier_step_cycles);
  wipe_carrier(reinterpret_cast<const std::int16_t*>(samples), n, re.data(), im.data(), cr, ci,
               static_cast<float>(w.real()), static_cast<float>(w.imag()));

  thread_local const CaCodeChips* cached_code = nullptr;
  thread_local const CaCodeChips* cached_noise = nullptr;
  thread_local std::unique_ptr<TwoPeriodCode> table, noise_table;
  if (cached_code != &code) {
    table = std::make_unique<TwoPeriodCode>(code);
    cached_code = &code;
  }
  if (cached_noise != &noise_code) {
    noise_table = std::make_unique<TwoPeriodCode>(noise_code);
    cached_noise = &noise_code;
  }
  const double half = 0.5 * s.spacing_chips;
  out.early = code_correlation(re.data(), im.data(), n, s.code_phase_chips + half, s.code_step_chips, table->levels);
  out.prompt = code_correlation(re.data(), im.data(), n, s.code_phase_chips, s.code_step_chips, table->levels);
  out.late = code_correlation(re.data(), im.data(), n, s.code_phase_chips - half + 1023.0, s.code_step_chips, table->levels);
  out.noise = code_correlation(re.data(), im.data(), n, s.code_phase_chips, s.code_step_chips, noise_table->levels);
  return out;
}

}  // namespace deepnav
