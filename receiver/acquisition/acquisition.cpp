#include "receiver/acquisition/acquisition.hpp"

#include <fftw3.h>
#include <fmt/format.h>
#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "receiver/acquisition/fft_search_kernels.hpp"
#include "receiver/acquisition/fftw_plan.hpp"
#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

using acquisition_kernels::add_power;
using acquisition_kernels::FftwBuffer;
using acquisition_kernels::multiply_spectra;
using acquisition_kernels::smooth_fft_size;

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
  return boost::math::gamma_q(static_cast<double>(k), x);
}

double acquisition_threshold(int k, double cells, double pfa) {
  if (!(pfa > 0.0 && pfa < 1.0)) throw std::invalid_argument("acquisition: pfa must be in (0, 1)");
  if (k < 1 || !(cells >= 1.0)) throw std::invalid_argument("acquisition: at least one block and one cell");
  const double per_cell = -std::expm1(std::log1p(-pfa) / cells);  // 1 - (1 - pfa)^(1/cells)
  return boost::math::gamma_q_inv(static_cast<double>(k), per_cell);
}

struct Acquisition::Impl {
  AcquisitionConfig cfg;
  int n = 0;   ///< samples per coherent block
  int nf = 0;  ///< FFT size: n, or the next fast size (the block is stretched to it)
  double samples_per_ms = 0;
  std::vector<double> dopplers;
  FftwBuffer in, out;
  std::optional<FftwPlan> forward, inverse;
  std::vector<std::vector<std::complex<float>>> code_spectra;  ///< conj(FFT(stretched replica)) per PRN (index prn - 1)
  std::vector<std::vector<float>> replicas;                    ///< at the sample rate, for the refinement
  std::vector<int> stretch_source;                             ///< sample of the block each of the nf FFT inputs takes

  explicit Impl(AcquisitionConfig c) : cfg(std::move(c)), in(1), out(1) {
    if (!(cfg.sample_rate_hz >= 1.023e6 && cfg.sample_rate_hz <= kMaxAcquisitionSampleRate_hz))
      throw std::invalid_argument(fmt::format("acquisition: sample rate {} Hz must be in [1.023 MHz, {:g} Hz]",
                                              cfg.sample_rate_hz, kMaxAcquisitionSampleRate_hz));
    if (!std::isfinite(cfg.if_hz) || std::abs(cfg.if_hz) >= cfg.sample_rate_hz / 2)
      throw std::invalid_argument(fmt::format("acquisition: IF {} Hz must be below half the sample rate ({} Hz)",
                                              cfg.if_hz, cfg.sample_rate_hz / 2));
    if (cfg.coherent_ms < 1 || cfg.coherent_ms > 10)
      throw std::invalid_argument("acquisition: coherent_ms must be 1..10");
    if (cfg.noncoherent < 1 || cfg.noncoherent > kMaxNoncoherent)
      throw std::invalid_argument(
          fmt::format("acquisition: noncoherent {} must be 1..{} (the search holds every block)", cfg.noncoherent,
                      kMaxNoncoherent));
    if (!(cfg.doppler_step_hz >= 0.0 && cfg.doppler_step_hz <= 10000.0))
      throw std::invalid_argument(
          fmt::format("acquisition: doppler_step {} Hz must be in [0, 10000] Hz (0: automatic)", cfg.doppler_step_hz));
    if (!(cfg.pfa > 0.0 && cfg.pfa < 1.0))
      throw std::invalid_argument(fmt::format("acquisition: pfa {} must be in (0, 1)", cfg.pfa));
    if (!(cfg.doppler_max_hz >= 0.0 && cfg.doppler_max_hz <= 50000.0))
      throw std::invalid_argument("acquisition: doppler_max must be in [0, 50000] Hz");
    if (cfg.prns.empty())
      for (int p = 1; p <= gps::kMaxPrn; ++p) cfg.prns.push_back(p);
    for (int p : cfg.prns)
      if (p < 1 || p > gps::kMaxPrn)
        throw std::invalid_argument("acquisition: PRN " + std::to_string(p) + " is not in 1..32");
    const double t_coh = cfg.coherent_ms * 1e-3;
    if (cfg.doppler_step_hz <= 0.0) cfg.doppler_step_hz = 2.0 / (3.0 * t_coh);
    n = static_cast<int>(std::floor(cfg.sample_rate_hz * t_coh));
    nf = smooth_fft_size(n);
    samples_per_ms = cfg.sample_rate_hz / 1000.0;
    // Stretching by nearest sample: FFT input j is block sample round(j n / nf), so the
    // grid's lags are in units of n / nf samples and the replica is drawn at fs nf / n.
    stretch_source.resize(static_cast<std::size_t>(nf));
    for (int j = 0; j < nf; ++j)
      stretch_source[static_cast<std::size_t>(j)] =
          std::min(n - 1, static_cast<int>(std::lround(static_cast<double>(j) * n / nf)));
    const double half_bins = std::floor(cfg.doppler_max_hz / cfg.doppler_step_hz + 1e-9);
    if (half_bins > 5000.0)
      throw std::invalid_argument(
          fmt::format("acquisition: a Doppler step of {} Hz over +-{} Hz is {:g} bins, at most "
                      "10001",
                      cfg.doppler_step_hz, cfg.doppler_max_hz, 2 * half_bins + 1));
    const int half = static_cast<int>(half_bins);
    for (int k = -half; k <= half; ++k) dopplers.push_back(k * cfg.doppler_step_hz);
    in = FftwBuffer(static_cast<std::size_t>(nf));  // nf >= n: holds a mixed block too
    out = FftwBuffer(static_cast<std::size_t>(nf));
    forward.emplace(nf, in.data, out.data, FFTW_FORWARD);
    inverse.emplace(nf, in.data, out.data, FFTW_BACKWARD);
    code_spectra.resize(gps::kMaxPrn);
    replicas.resize(gps::kMaxPrn);
    for (int p : cfg.prns) {
      replicas[static_cast<std::size_t>(p - 1)] = code_replica(p, n, cfg.sample_rate_hz);
      const std::vector<float> stretched = code_replica(p, nf, cfg.sample_rate_hz * nf / n);
      for (int k = 0; k < nf; ++k) in.c()[k] = {stretched[static_cast<std::size_t>(k)], 0.0f};
      forward->execute();
      auto& spec = code_spectra[static_cast<std::size_t>(p - 1)];
      spec.resize(static_cast<std::size_t>(nf));
      for (int k = 0; k < nf; ++k) spec[static_cast<std::size_t>(k)] = std::conj(out.c()[k]);
    }
  }

  /// Mean of each coherent block: removed before mixing, since ADC offsets (odd-level 2-bit
  /// converters, real IF) would otherwise correlate with every code near zero Doppler.
  std::vector<std::complex<double>> block_means(std::span<const Sample> x, int blocks) const {
    std::vector<std::complex<double>> means(static_cast<std::size_t>(blocks));
    for (int b = 0; b < blocks; ++b) {
      std::complex<double> dc = 0.0;
      for (int k = 0; k < n; ++k) {
        const auto& s = x[static_cast<std::size_t>(static_cast<std::int64_t>(b) * n + k)];
        dc += std::complex<double>(s.real(), s.imag());
      }
      means[static_cast<std::size_t>(b)] = dc / static_cast<double>(n);
    }
    return means;
  }

  /// (x[first + k] - mean) * exp(-j 2 pi (IF + f) t) for k in [0, count), t from sample 0.
  void mix(std::span<const Sample> x, std::int64_t first, int count, std::complex<double> block_mean, double f_hz,
           std::complex<float>* dst) const {
    const std::complex<float> mean(block_mean);
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

  /// Mixes block b (mean `block_mean`) at f into the FFT input, stretched to nf samples when nf > n.
  void mix_block(std::span<const Sample> x, int b, std::complex<double> block_mean, double f_hz,
                 std::vector<std::complex<float>>& scratch) {
    const std::int64_t first = static_cast<std::int64_t>(b) * n;
    if (nf == n) {
      mix(x, first, n, block_mean, f_hz, in.c());
      return;
    }
    mix(x, first, n, block_mean, f_hz, scratch.data());
    for (int j = 0; j < nf; ++j)
      in.c()[j] = scratch[static_cast<std::size_t>(stretch_source[static_cast<std::size_t>(j)])];
  }

  /// Fine Doppler search at one code phase, at the sample rate. Each block's samples are
  /// code-wiped at `lag` and mixed down at the coarse frequency once, then summed over
  /// chunks of about 8 us: a trial frequency f then costs one rotation per chunk, at the
  /// offset f - coarse (within a few kHz, so a chunk's own phase turns by under 0.1 rad,
  /// and the chunk is rotated from its centre).
  class DopplerRefiner {
   public:
    /// `storage` is reused between calls (a fresh buffer per PRN costs page faults).
    DopplerRefiner(const Impl& acq, std::span<const Sample> x, const std::vector<std::complex<double>>& means, int prn,
                   int lag, double coarse_hz, std::vector<std::complex<double>>& storage)
        : fs_(acq.cfg.sample_rate_hz),
          coarse_hz_(coarse_hz),
          blocks_(static_cast<int>(means.size())),
          n_(acq.n),
          chunk_(std::max(1, static_cast<int>(fs_ / 128e3))),
          per_block_((n_ + chunk_ - 1) / chunk_),
          chunks_(storage) {
      const int n = n_, blocks = blocks_;
      const auto& r = acq.replicas[static_cast<std::size_t>(prn - 1)];
      chunks_.assign(static_cast<std::size_t>(blocks) * static_cast<std::size_t>(per_block_), 0.0);
      const double w = -2.0 * M_PI * (acq.cfg.if_hz + coarse_hz) / fs_;
      const std::complex<double> step = std::polar(1.0, w);
      for (int b = 0; b < blocks; ++b) {
        const std::int64_t first = static_cast<std::int64_t>(b) * n;
        const std::complex<double> mean = means[static_cast<std::size_t>(b)];
        std::complex<double>* out = chunks_.data() + static_cast<std::size_t>(b) * static_cast<std::size_t>(per_block_);
        // Written out: std::complex's operator* checks for NaN/inf results and does not vectorise.
        double rot_re = 1.0, rot_im = 0.0;
        for (int k = 0, j = (n - lag % n) % n; k < n; ++k, j = (j + 1 == n ? 0 : j + 1)) {
          const auto& smp = x[static_cast<std::size_t>(first + k)];
          const double code = r[static_cast<std::size_t>(j)];
          const double re = (smp.real() - mean.real()) * code, im = (smp.imag() - mean.imag()) * code;
          out[k / chunk_] += std::complex<double>(re * rot_re - im * rot_im, re * rot_im + im * rot_re);
          const double next_re = rot_re * step.real() - rot_im * step.imag();
          rot_im = rot_re * step.imag() + rot_im * step.real();
          rot_re = next_re;
          if ((k & 1023) == 1023) {  // keep the recursion on the unit circle
            const double norm = std::hypot(rot_re, rot_im);
            rot_re /= norm;
            rot_im /= norm;
          }
        }
      }
    }
    /// Sum over blocks of the coherent power at f (same units as the direct correlation).
    double power(double f_hz) const {
      const double w = -2.0 * M_PI * (f_hz - coarse_hz_) / fs_;
      double total = 0.0;
      for (int b = 0; b < blocks_; ++b) {
        const std::complex<double>* z =
            chunks_.data() + static_cast<std::size_t>(b) * static_cast<std::size_t>(per_block_);
        std::complex<double> acc = 0.0;
        for (int a = 0; a < per_block_; ++a) {
          const int len = std::min(chunk_, n_ - a * chunk_);
          acc += z[a] * std::polar(1.0, w * (a * chunk_ + 0.5 * (len - 1)));
        }
        total += std::norm(acc);
      }
      return total;
    }

   private:
    double fs_, coarse_hz_;
    int blocks_, n_, chunk_, per_block_;
    std::vector<std::complex<double>>& chunks_;
  };
  std::array<std::vector<std::complex<double>>, 2> refiner_storage;

  /// The search's working memory, kept between searches (tens of MB for all 32 PRNs at a
  /// few Msps: allocated again each time, it made the run's peak memory vary).
  std::vector<std::complex<float>> scratch;
  std::vector<std::vector<std::complex<float>>> spectra;
  std::vector<std::vector<float>> grids;

  std::vector<AcquisitionResult> search(std::span<const Sample> x, const std::vector<int>& prns) {
    for (int p : prns)
      if (std::find(cfg.prns.begin(), cfg.prns.end(), p) == cfg.prns.end())
        throw std::invalid_argument("acquisition: PRN " + std::to_string(p) + " is not one of the configured PRNs");
    const int blocks =
        static_cast<int>(std::min<std::int64_t>(cfg.noncoherent, static_cast<std::int64_t>(x.size()) / n));
    if (blocks < 1) {
      throw std::invalid_argument("acquisition: need at least " + std::to_string(n) +
                                  " samples (one coherent block), got " + std::to_string(x.size()));
    }
    // Per Doppler bin, the mixed input's spectra (one per block) are made once and serve
    // every PRN while they are still in cache; each PRN's grid collects its rows.
    const std::size_t nb = dopplers.size();
    const auto cells_per_row = static_cast<std::size_t>(nf);
    scratch.resize(static_cast<std::size_t>(n));
    if (spectra.size() < static_cast<std::size_t>(blocks)) spectra.resize(static_cast<std::size_t>(blocks));
    for (auto& spectrum : spectra) spectrum.resize(cells_per_row);
    if (grids.size() < prns.size()) grids.resize(prns.size());
    for (std::size_t p = 0; p < prns.size(); ++p) grids[p].assign(nb * cells_per_row, 0.0f);
    const std::vector<std::complex<double>> means = block_means(x, blocks);
    for (std::size_t d = 0; d < nb; ++d) {
      for (int b = 0; b < blocks; ++b) {
        mix_block(x, b, means[static_cast<std::size_t>(b)], dopplers[d], scratch);
        forward->execute();
        std::copy(out.c(), out.c() + nf, spectra[static_cast<std::size_t>(b)].begin());
      }
      for (std::size_t p = 0; p < prns.size(); ++p) {
        const auto& code = code_spectra[static_cast<std::size_t>(prns[p] - 1)];
        float* row = grids[p].data() + d * cells_per_row;
        for (int b = 0; b < blocks; ++b) {
          multiply_spectra(spectra[static_cast<std::size_t>(b)].data(), code.data(), in.c(), nf);
          inverse->execute();
          add_power(out.c(), row, nf);
        }
      }
    }
    const double cells = static_cast<double>(nb) * std::floor(samples_per_ms);
    const double threshold = acquisition_threshold(blocks, cells, cfg.pfa);
    std::vector<AcquisitionResult> results;
    for (std::size_t p = 0; p < prns.size(); ++p) results.push_back(evaluate(x, means, prns[p], grids[p], threshold));
    acquisition_kernels::reject_cross_correlations(results, cfg.cross_correlation_margin_db);
    return results;
  }

  /// Mean grid cell more than 1.5 chips (in code phase modulo 1 ms) from the peak's lag.
  double noise_floor(const std::vector<float>& grid, int lag) const {
    const double lags_per_ms = samples_per_ms * nf / n;
    const double exclusion = 1.5 * lags_per_ms / gps::kCodeLength_chips;
    std::vector<float> weight(static_cast<std::size_t>(nf));
    for (int k = 0; k < nf; ++k) {
      double off = std::fmod(std::abs(static_cast<double>(k - lag)), lags_per_ms);
      off = std::min(off, lags_per_ms - off);
      weight[static_cast<std::size_t>(k)] = off <= exclusion ? 0.0f : 1.0f;
    }
    const double count = std::accumulate(weight.begin(), weight.end(), 0.0) * static_cast<double>(dopplers.size());
    double sum = 0.0;
    for (std::size_t d = 0; d < dopplers.size(); ++d) {
      const float* row = grid.data() + d * static_cast<std::size_t>(nf);
      sum += std::inner_product(row, row + nf, weight.data(), 0.0);
    }
    return count > 0 ? sum / count : 1.0;
  }

  /// `means`: one per coherent block searched.
  AcquisitionResult evaluate(std::span<const Sample> x, const std::vector<std::complex<double>>& means, int prn,
                             const std::vector<float>& grid, double threshold) {
    const int blocks = static_cast<int>(means.size());
    const auto peak_it = std::max_element(grid.begin(), grid.end());
    const auto peak_index = static_cast<std::size_t>(std::distance(grid.begin(), peak_it));
    const std::size_t d_peak = peak_index / static_cast<std::size_t>(nf);
    const int lag = static_cast<int>(peak_index % static_cast<std::size_t>(nf));
    const double cell_mean = noise_floor(grid, lag);
    AcquisitionResult r;
    r.prn = prn;
    r.threshold = threshold;
    r.statistic = *peak_it / (cell_mean / blocks);
    r.detected = r.statistic > threshold;

    // Delay: parabolic interpolation between neighbouring lags, converted from the grid's
    // lag unit (n / nf samples) and folded into one code period.
    const float* row = grid.data() + d_peak * static_cast<std::size_t>(nf);
    const double ym = row[(lag - 1 + nf) % nf], y0 = row[lag], yp = row[(lag + 1) % nf];
    const double denom = ym - 2.0 * y0 + yp;
    const double frac = denom < 0.0 ? std::clamp(0.5 * (ym - yp) / denom, -0.5, 0.5) : 0.0;
    const double delay = (lag + frac) * n / nf;
    r.delay_samples = std::fmod(delay + samples_per_ms, samples_per_ms);
    r.code_phase_chips = std::fmod(
        gps::kCodeLength_chips - r.delay_samples * gps::kCodeRate_cps / cfg.sample_rate_hz + gps::kCodeLength_chips,
        static_cast<double>(gps::kCodeLength_chips));
    if (!r.detected) {
      // Nothing to track: the coarse bin and the grid's peak-to-floor ratio are enough (a
      // stretched block's repeated samples raise that ratio by nf / n, taken out here).
      r.doppler_hz = dopplers[d_peak];
      const double snr = (*peak_it / cell_mean - 1.0) * n / nf;
      r.cn0_dbhz = snr > 0.0 ? 10.0 * std::log10(snr / (cfg.coherent_ms * 1e-3)) : 0.0;
      return r;
    }

    // Doppler: finer search around the peak bin at the peak's code phase (at whichever of
    // the two whole samples around the delay correlates better), then a parabola through
    // the best fine cell and its neighbours.
    const double fine_step = cfg.doppler_step_hz / 10.0;
    std::vector<double> fine(21);
    int best_i = 0;
    const auto below = static_cast<int>(std::floor(r.delay_samples));
    const DopplerRefiner early(*this, x, means, prn, below % n, dopplers[d_peak], refiner_storage[0]);
    const DopplerRefiner late(*this, x, means, prn, (below + 1) % n, dopplers[d_peak], refiner_storage[1]);
    const DopplerRefiner& refiner = early.power(dopplers[d_peak]) >= late.power(dopplers[d_peak]) ? early : late;
    for (int i = -10; i <= 10; ++i) {
      fine[static_cast<std::size_t>(i + 10)] = refiner.power(dopplers[d_peak] + i * fine_step);
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
    // C/N0 from the coherent SNR. A grid cell holds nf^2 |sum over nf samples|^2: its noise
    // is nf^3 / n times the direct correlation's over n samples.
    const double noise = cell_mean / blocks * n / (static_cast<double>(nf) * nf * nf);
    const double snr = (best_p / blocks - noise) / noise;
    r.cn0_dbhz = snr > 0.0 ? 10.0 * std::log10(snr / (cfg.coherent_ms * 1e-3)) : 0.0;
    return r;
  }
};

std::string if_sample_problem(std::span<const Sample> samples, bool real) {
  if (samples.empty()) return "no samples";
  const auto n = static_cast<double>(samples.size());
  for (int component = 0; component < (real ? 1 : 2); ++component) {
    double sum = 0.0, sum_sq = 0.0;
    for (const Sample& s : samples) {
      const double x = component == 0 ? s.real() : s.imag();
      sum += x;
      sum_sq += x * x;
    }
    const double mean = sum / n;
    const double spread = std::sqrt(std::max(0.0, sum_sq / n - mean * mean));
    const char* name = component == 0 ? "I" : "Q";
    if (spread == 0.0)
      return fmt::format("every {} sample is {}: not IF samples (a blank file, or the wrong format)", name, mean);
    if (std::abs(mean) > spread)
      return fmt::format(
          "the {} samples average {:.3g} with a spread of only {:.3g}: a front end's samples are noise "
          "around zero, so this is not an IF file of this format (a text file? unsigned samples?)",
          name, mean, spread);
  }
  return {};
}

Acquisition::Acquisition(AcquisitionConfig config) : impl_(std::make_unique<Impl>(std::move(config))) {}
Acquisition::~Acquisition() = default;

std::int64_t Acquisition::samples_needed() const {
  return static_cast<std::int64_t>(impl_->n) * impl_->cfg.noncoherent;
}

std::vector<AcquisitionResult> Acquisition::search(std::span<const Sample> samples) {
  return impl_->search(samples, impl_->cfg.prns);
}

std::vector<AcquisitionResult> Acquisition::search(std::span<const Sample> samples, const std::vector<int>& prns) {
  return impl_->search(samples, prns);
}

}  // namespace deepnav
