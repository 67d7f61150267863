#include "receiver/acquisition.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

/// fftwf_complex buffers owned RAII-style (FFTW's allocator keeps SIMD alignment).
struct FftwBuffer {
  explicit FftwBuffer(std::size_t n) : data(fftwf_alloc_complex(n)), size(n) {
    if (data == nullptr) throw std::bad_alloc();
  }
  ~FftwBuffer() { fftwf_free(data); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  FftwBuffer(FftwBuffer&& o) noexcept : data(o.data), size(o.size) { o.data = nullptr; }
  FftwBuffer& operator=(FftwBuffer&& o) noexcept {
    std::swap(data, o.data);
    std::swap(size, o.size);
    return *this;
  }
  std::complex<float>* c() { return reinterpret_cast<std::complex<float>*>(data); }
  fftwf_complex* data;
  std::size_t size;
};

/// Code replica of `n` samples at fs, chip 0 at sample 0.
std::vector<float> code_replica(int prn, int n, double fs) {
  const auto& code = ca_code_chips(prn);
  std::vector<float> r(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const auto chip = static_cast<long long>(std::floor(k * gps::kCodeRate_cps / fs)) % gps::kCodeLength_chips;
    r[static_cast<std::size_t>(k)] = static_cast<float>(code[static_cast<std::size_t>(chip)]);
  }
  return r;
}

}  // namespace

double gamma_upper_tail(int k, double x) {
  if (x <= 0.0) return 1.0;
  // e^-x sum_{i<k} x^i / i!, summed in logs to stay finite for large x.
  double term = 1.0, sum = 1.0;
  for (int i = 1; i < k; ++i) {
    term *= x / i;
    sum += term;
  }
  return std::exp(-x + std::log(sum));
}

double acquisition_threshold(int k, double cells, double pfa) {
  if (!(pfa > 0.0 && pfa < 1.0)) throw std::invalid_argument("acquisition: pfa must be in (0, 1)");
  const double per_cell = -std::expm1(std::log1p(-pfa) / cells);  // 1 - (1 - pfa)^(1/cells)
  double lo = 0.0, hi = 10.0 * k + 100.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (gamma_upper_tail(k, mid) > per_cell ? lo : hi) = mid;
  }
  return hi;
}

struct Acquisition::Impl {
  AcquisitionConfig cfg;
  int n = 0;                 ///< samples per coherent block
  double samples_per_ms = 0;
  std::vector<double> dopplers;
  FftwBuffer in, out;
  fftwf_plan forward = nullptr, inverse = nullptr;
  std::vector<std::vector<std::complex<float>>> code_spectra;  ///< conj(FFT(replica)) per PRN (index prn - 1)
  std::vector<std::vector<float>> replicas;

  explicit Impl(AcquisitionConfig c) : cfg(std::move(c)), in(1), out(1) {
    if (!(cfg.sample_rate_hz >= 1.023e6)) throw std::invalid_argument("acquisition: sample rate must be at least 1.023 MHz");
    if (cfg.coherent_ms < 1 || cfg.coherent_ms > 10) throw std::invalid_argument("acquisition: coherent_ms must be 1..10");
    if (cfg.noncoherent < 1) throw std::invalid_argument("acquisition: noncoherent must be at least 1");
    if (!(cfg.doppler_max_hz >= 0.0 && cfg.doppler_max_hz <= 50000.0))
      throw std::invalid_argument("acquisition: doppler_max must be in [0, 50000] Hz");
    if (cfg.prns.empty())
      for (int p = 1; p <= gps::kMaxPrn; ++p) cfg.prns.push_back(p);
    for (int p : cfg.prns)
      if (p < 1 || p > gps::kMaxPrn) throw std::invalid_argument("acquisition: PRN " + std::to_string(p) + " is not in 1..32");
    const double t_coh = cfg.coherent_ms * 1e-3;
    if (cfg.doppler_step_hz <= 0.0) cfg.doppler_step_hz = 2.0 / (3.0 * t_coh);
    n = static_cast<int>(std::floor(cfg.sample_rate_hz * t_coh));
    samples_per_ms = cfg.sample_rate_hz / 1000.0;
    const int half = static_cast<int>(std::floor(cfg.doppler_max_hz / cfg.doppler_step_hz + 1e-9));
    for (int k = -half; k <= half; ++k) dopplers.push_back(k * cfg.doppler_step_hz);
    in = FftwBuffer(static_cast<std::size_t>(n));
    out = FftwBuffer(static_cast<std::size_t>(n));
    forward = fftwf_plan_dft_1d(n, in.data, out.data, FFTW_FORWARD, FFTW_ESTIMATE);
    inverse = fftwf_plan_dft_1d(n, in.data, out.data, FFTW_BACKWARD, FFTW_ESTIMATE);
    if (forward == nullptr || inverse == nullptr) throw std::runtime_error("acquisition: FFTW planning failed");
    code_spectra.resize(gps::kMaxPrn);
    replicas.resize(gps::kMaxPrn);
    for (int p : cfg.prns) {
      auto& r = replicas[static_cast<std::size_t>(p - 1)];
      r = code_replica(p, n, cfg.sample_rate_hz);
      for (int k = 0; k < n; ++k) in.c()[k] = {r[static_cast<std::size_t>(k)], 0.0f};
      fftwf_execute(forward);
      auto& spec = code_spectra[static_cast<std::size_t>(p - 1)];
      spec.resize(static_cast<std::size_t>(n));
      for (int k = 0; k < n; ++k) spec[static_cast<std::size_t>(k)] = std::conj(out.c()[k]);
    }
  }
  ~Impl() {
    if (forward) fftwf_destroy_plan(forward);
    if (inverse) fftwf_destroy_plan(inverse);
  }

  /// (x[first + k] - dc) * exp(-j 2 pi (IF + f) t) for k in [0, count), t from sample 0. The
  /// block's mean is removed first: ADC offsets (odd-level 2-bit converters, real IF) would
  /// otherwise correlate with every code near zero Doppler.
  void mix(std::span<const Sample> x, std::int64_t first, int count, double f_hz, std::complex<float>* dst) const {
    std::complex<double> dc = 0.0;
    for (int k = 0; k < count; ++k) {
      const auto& s = x[static_cast<std::size_t>(first + k)];
      dc += std::complex<double>(s.real(), s.imag());
    }
    const std::complex<float> mean(dc / static_cast<double>(count));
    const double w = -2.0 * M_PI * (cfg.if_hz + f_hz) / cfg.sample_rate_hz;
    std::complex<double> rot = std::polar(1.0, w * static_cast<double>(first));
    const std::complex<double> step = std::polar(1.0, w);
    for (int k = 0; k < count; ++k) {
      const auto& s = x[static_cast<std::size_t>(first + k)];
      dst[k] = (std::complex<float>(static_cast<float>(s.real()), static_cast<float>(s.imag())) - mean) *
               std::complex<float>(rot);
      rot *= step;
      if ((k & 1023) == 1023) rot /= std::abs(rot);  // keep the recursion on the unit circle
    }
  }

  /// Sum over blocks of |sum_n x mixed at f * replica shifted by lag|^2 (direct, for refinement).
  double power_at(std::span<const Sample> x, int blocks, int prn, double f_hz, double lag) const {
    const auto& r = replicas[static_cast<std::size_t>(prn - 1)];
    std::vector<std::complex<float>> mixed(static_cast<std::size_t>(n));
    const int ilag = static_cast<int>(std::lround(lag));
    double total = 0.0;
    for (int b = 0; b < blocks; ++b) {
      mix(x, static_cast<std::int64_t>(b) * n, n, f_hz, mixed.data());
      std::complex<double> acc = 0.0;
      for (int k = 0; k < n; ++k) {
        const int j = ((k - ilag) % n + n) % n;
        acc += std::complex<double>(mixed[static_cast<std::size_t>(k)]) * static_cast<double>(r[static_cast<std::size_t>(j)]);
      }
      total += std::norm(acc);
    }
    return total;
  }

  std::vector<AcquisitionResult> search(std::span<const Sample> x) {
    const int blocks = static_cast<int>(std::min<std::int64_t>(cfg.noncoherent, static_cast<std::int64_t>(x.size()) / n));
    if (blocks < 1) {
      throw std::invalid_argument("acquisition: need at least " + std::to_string(n) + " samples (one coherent block), got " +
                                  std::to_string(x.size()));
    }
    // Spectra of the mixed input: one per Doppler bin and block, shared by every PRN.
    const std::size_t nb = dopplers.size();
    std::vector<std::vector<std::complex<float>>> spectra(nb * static_cast<std::size_t>(blocks));
    for (std::size_t d = 0; d < nb; ++d) {
      for (int b = 0; b < blocks; ++b) {
        mix(x, static_cast<std::int64_t>(b) * n, n, dopplers[d], in.c());
        fftwf_execute(forward);
        spectra[d * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(b)].assign(out.c(), out.c() + n);
      }
    }
    const double cells = static_cast<double>(nb) * std::floor(samples_per_ms);
    const double threshold = acquisition_threshold(blocks, cells, cfg.pfa);
    std::vector<float> grid(nb * static_cast<std::size_t>(n));
    std::vector<AcquisitionResult> results;
    for (int prn : cfg.prns) {
      const auto& spec = code_spectra[static_cast<std::size_t>(prn - 1)];
      std::fill(grid.begin(), grid.end(), 0.0f);
      for (std::size_t d = 0; d < nb; ++d) {
        float* row = grid.data() + d * static_cast<std::size_t>(n);
        for (int b = 0; b < blocks; ++b) {
          const auto& s = spectra[d * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(b)];
          for (int k = 0; k < n; ++k) in.c()[k] = s[static_cast<std::size_t>(k)] * spec[static_cast<std::size_t>(k)];
          fftwf_execute(inverse);
          for (int k = 0; k < n; ++k) row[k] += std::norm(out.c()[k]);
        }
      }
      results.push_back(evaluate(x, blocks, prn, grid, threshold));
    }
    reject_cross_correlations(results);
    return results;
  }

  void reject_cross_correlations(std::vector<AcquisitionResult>& results) const {
    double strongest = -1e9;
    for (const auto& r : results)
      if (r.detected) strongest = std::max(strongest, r.cn0_dbhz);
    for (auto& r : results) {
      if (r.detected && r.cn0_dbhz < strongest - cfg.cross_correlation_margin_db) {
        r.detected = false;
        r.cross_correlation_suspect = true;
      }
    }
  }

  AcquisitionResult evaluate(std::span<const Sample> x, int blocks, int prn, const std::vector<float>& grid,
                             double threshold) const {
    const auto peak_it = std::max_element(grid.begin(), grid.end());
    const auto peak_index = static_cast<std::size_t>(std::distance(grid.begin(), peak_it));
    const std::size_t d_peak = peak_index / static_cast<std::size_t>(n);
    const int lag = static_cast<int>(peak_index % static_cast<std::size_t>(n));
    // Noise floor: every cell more than 1.5 chips (in code phase modulo 1 ms) from the peak.
    const double exclusion = 1.5 * cfg.sample_rate_hz / gps::kCodeRate_cps;
    double sum = 0.0;
    std::size_t count = 0;
    for (int k = 0; k < n; ++k) {
      double off = std::fmod(std::abs(static_cast<double>(k - lag)), samples_per_ms);
      off = std::min(off, samples_per_ms - off);
      if (off <= exclusion) continue;
      for (std::size_t d = 0; d < dopplers.size(); ++d) sum += grid[d * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)];
      count += dopplers.size();
    }
    const double cell_mean = count > 0 ? sum / static_cast<double>(count) : 1.0;
    AcquisitionResult r;
    r.prn = prn;
    r.threshold = threshold;
    r.statistic = *peak_it / (cell_mean / blocks);
    r.detected = r.statistic > threshold;

    // Delay: parabolic interpolation between neighbouring lags, folded into one code period.
    const float* row = grid.data() + d_peak * static_cast<std::size_t>(n);
    const double ym = row[(lag - 1 + n) % n], y0 = row[lag], yp = row[(lag + 1) % n];
    const double denom = ym - 2.0 * y0 + yp;
    const double frac = denom < 0.0 ? std::clamp(0.5 * (ym - yp) / denom, -0.5, 0.5) : 0.0;
    r.delay_samples = std::fmod(lag + frac + samples_per_ms, samples_per_ms);
    r.code_phase_chips = std::fmod(gps::kCodeLength_chips - r.delay_samples * gps::kCodeRate_cps / cfg.sample_rate_hz +
                                       gps::kCodeLength_chips, static_cast<double>(gps::kCodeLength_chips));

    // Doppler: finer search around the peak bin at the peak's code phase, then a parabola
    // through the best fine cell and its neighbours.
    const double fine_step = cfg.doppler_step_hz / 10.0;
    std::vector<double> fine(21);
    int best_i = 0;
    for (int i = -10; i <= 10; ++i) {
      fine[static_cast<std::size_t>(i + 10)] = power_at(x, blocks, prn, dopplers[d_peak] + i * fine_step, lag);
      if (fine[static_cast<std::size_t>(i + 10)] > fine[static_cast<std::size_t>(best_i + 10)]) best_i = i;
    }
    double best_f = dopplers[d_peak] + best_i * fine_step;
    const double best_p = fine[static_cast<std::size_t>(best_i + 10)];
    if (best_i > -10 && best_i < 10) {
      const double pm = fine[static_cast<std::size_t>(best_i + 9)], pp = fine[static_cast<std::size_t>(best_i + 11)];
      const double curvature = pm - 2.0 * best_p + pp;
      if (curvature < 0.0) best_f += std::clamp(0.5 * (pm - pp) / curvature, -0.5, 0.5) * fine_step;
    }
    r.doppler_hz = best_f;
    // C/N0 from the coherent SNR: grid cells carry the FFT scale n^2 relative to power_at.
    const double noise = cell_mean / blocks / (static_cast<double>(n) * n);
    const double snr = (best_p / blocks - noise) / noise;
    r.cn0_dbhz = snr > 0.0 ? 10.0 * std::log10(snr / (cfg.coherent_ms * 1e-3)) : 0.0;
    return r;
  }
};

Acquisition::Acquisition(AcquisitionConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}
Acquisition::~Acquisition() = default;

std::int64_t Acquisition::samples_needed() const {
  return static_cast<std::int64_t>(impl_->n) * impl_->cfg.noncoherent;
}

std::vector<AcquisitionResult> Acquisition::search(std::span<const Sample> samples) { return impl_->search(samples); }

}  // namespace deepnav
