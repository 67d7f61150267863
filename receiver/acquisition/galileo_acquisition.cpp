#include "receiver/acquisition/galileo_acquisition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <stdexcept>
#include <string>

#include "receiver/acquisition/acquisition.hpp"
#include "receiver/acquisition/e1_code_phase_refinement.hpp"
#include "receiver/acquisition/fft_search_kernels.hpp"
#include "receiver/acquisition/fftw_plan.hpp"
#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/e1_modulation.hpp"
#include "signals/galileo/galileo_constants.hpp"

namespace deepnav {
namespace {

using acquisition_kernels::add_power;
using acquisition_kernels::FftwBuffer;
using acquisition_kernels::multiply_spectra;
using acquisition_kernels::smooth_fft_size;
using galileo::kE1CodeLength_chips;
using galileo::kE1CodeRate_cps;

/// The most memory the search's per-block spectra may take (the rest is a few rows per PRN).
constexpr double kMaxSpectraBytes = 1024.0 * 1048576.0;

/// Cells within this many chips (modulo a code period) of the peak are left out of the noise floor:
/// the BOC(1,1) correlation is zero from one chip on.
constexpr double kPeakExclusion_chips = 1.5;

/// What the search keeps of one PRN's grid: each lag's sum over the Doppler bins, and the
/// row (Doppler bin) holding the largest cell.
struct GridSummary {
  std::vector<double> lag_sums;
  std::vector<float> peak_row;
  std::size_t peak_bin = 0;
  int peak_lag = 0;
  float peak = -1.0f;

  void reset(int nf) {
    lag_sums.assign(static_cast<std::size_t>(nf), 0.0);
    peak_row.assign(static_cast<std::size_t>(nf), 0.0f);
    peak = -1.0f;
  }
  void add_row(const std::vector<float>& row, std::size_t bin) {
    for (std::size_t k = 0; k < row.size(); ++k) lag_sums[k] += row[k];
    const auto it = std::max_element(row.begin(), row.end());
    if (*it > peak) {
      peak = *it;
      peak_bin = bin;
      peak_lag = static_cast<int>(std::distance(row.begin(), it));
      peak_row = row;
    }
  }
};

}  // namespace

struct GalileoAcquisition::Impl {
  GalileoAcquisitionConfig cfg;
  int n = 0;   ///< samples per coherent block (one code period)
  int nf = 0;  ///< FFT size: n, or the next fast size (the block is stretched to it, as for GPS)
  double samples_per_period = 0;
  std::vector<double> dopplers;
  FftwBuffer in, out;
  std::optional<FftwPlan> forward, inverse;
  /// conj(FFT(stretched BOC(1,1) replica)) of E1-B and E1-C per PRN (index prn - 1).
  std::vector<std::vector<std::complex<float>>> spectra_b, spectra_c;
  std::vector<int> stretch_source;
  E1CodePhaseRefiner refiner;

  explicit Impl(GalileoAcquisitionConfig c)
      : cfg(validated(std::move(c))), in(1), out(1), refiner(cfg.sample_rate_hz, cfg.if_hz) {
    const double t_coh = galileo::kE1CodePeriod_s;
    n = static_cast<int>(std::floor(cfg.sample_rate_hz * t_coh));
    nf = smooth_fft_size(n);
    samples_per_period = cfg.sample_rate_hz * t_coh;
    // Every block's spectrum is held (complex floats) while the PRNs are searched.
    const double spectra_bytes = static_cast<double>(cfg.noncoherent) * nf * sizeof(std::complex<float>);
    if (spectra_bytes > kMaxSpectraBytes)
      throw std::invalid_argument(
          fmt::format("Galileo acquisition: noncoherent {} blocks of 4 ms at {} Hz would hold {:.0f} MiB of spectra, "
                      "at most {:.0f} "
                      "MiB: fewer blocks",
                      cfg.noncoherent, cfg.sample_rate_hz, spectra_bytes / 1048576.0, kMaxSpectraBytes / 1048576.0));
    stretch_source.resize(static_cast<std::size_t>(nf));
    for (int j = 0; j < nf; ++j)
      stretch_source[static_cast<std::size_t>(j)] =
          std::min(n - 1, static_cast<int>(std::lround(static_cast<double>(j) * n / nf)));
    const int half = static_cast<int>(std::floor(cfg.doppler_max_hz / cfg.doppler_step_hz + 1e-9));
    for (int k = -half; k <= half; ++k) dopplers.push_back(k * cfg.doppler_step_hz);
    in = FftwBuffer(static_cast<std::size_t>(nf));
    out = FftwBuffer(static_cast<std::size_t>(nf));
    forward.emplace(nf, in.data, out.data, FFTW_FORWARD);
    inverse.emplace(nf, in.data, out.data, FFTW_BACKWARD);
    spectra_b.resize(galileo::kMaxPrn);
    spectra_c.resize(galileo::kMaxPrn);
    const double chips_per_sample = kE1CodeRate_cps / (cfg.sample_rate_hz * nf / n);
    for (int p : cfg.prns) {
      spectra_b[static_cast<std::size_t>(p - 1)] = code_spectrum(galileo::e1b_code_chips(p), chips_per_sample);
      spectra_c[static_cast<std::size_t>(p - 1)] = code_spectrum(galileo::e1c_code_chips(p), chips_per_sample);
    }
  }

  static GalileoAcquisitionConfig validated(GalileoAcquisitionConfig cfg) {
    if (!(cfg.sample_rate_hz >= kGalileoMinSampleRate_hz && cfg.sample_rate_hz <= kMaxAcquisitionSampleRate_hz))
      throw std::invalid_argument(fmt::format(
          "Galileo acquisition: sample rate {} Hz must be in [{:g} Hz, {:g} Hz] (BOC(1,1)'s main lobes reach "
          "+-2 MHz)",
          cfg.sample_rate_hz, kGalileoMinSampleRate_hz, kMaxAcquisitionSampleRate_hz));
    if (!std::isfinite(cfg.if_hz) || std::abs(cfg.if_hz) >= cfg.sample_rate_hz / 2)
      throw std::invalid_argument(
          fmt::format("Galileo acquisition: IF {} Hz must be below half the sample rate ({} Hz)", cfg.if_hz,
                      cfg.sample_rate_hz / 2));
    if (cfg.noncoherent < 1 || cfg.noncoherent > kMaxNoncoherent)
      throw std::invalid_argument(fmt::format("Galileo acquisition: noncoherent {} must be 1..{} (4 ms blocks)",
                                              cfg.noncoherent, kMaxNoncoherent));
    if (!(cfg.doppler_step_hz > 0.0 && cfg.doppler_step_hz <= 250.0))
      throw std::invalid_argument(fmt::format(
          "Galileo acquisition: doppler_step {} Hz must be in (0, 250] Hz (a 4 ms block loses 3.9 dB half a 250 Hz "
          "bin off)",
          cfg.doppler_step_hz));
    if (!(cfg.doppler_max_hz >= 0.0 && cfg.doppler_max_hz <= 50000.0))
      throw std::invalid_argument("Galileo acquisition: doppler_max must be in [0, 50000] Hz");
    if (std::floor(cfg.doppler_max_hz / cfg.doppler_step_hz + 1e-9) > 5000.0)
      throw std::invalid_argument(
          fmt::format("Galileo acquisition: a Doppler step of {} Hz over +-{} Hz is more than 10001 bins",
                      cfg.doppler_step_hz, cfg.doppler_max_hz));
    if (!(cfg.pfa > 0.0 && cfg.pfa < 1.0))
      throw std::invalid_argument(fmt::format("Galileo acquisition: pfa {} must be in (0, 1)", cfg.pfa));
    if (cfg.prns.empty())
      for (int p = 1; p <= kGalileoMaxSvid; ++p) cfg.prns.push_back(p);
    for (int p : cfg.prns)
      if (p < 1 || p > galileo::kMaxPrn)
        throw std::invalid_argument(
            fmt::format("Galileo acquisition: PRN {} is not in 1..{} (the E1 codes defined)", p, galileo::kMaxPrn));
    return cfg;
  }

  std::vector<std::complex<float>> code_spectrum(const galileo::E1CodeChips& code, double chips_per_sample) {
    const std::vector<float> replica =
        galileo::e1_replica(code, galileo::E1Subcarrier::kBoc11, 0.0, chips_per_sample, static_cast<std::size_t>(nf));
    for (int k = 0; k < nf; ++k) in.c()[k] = {replica[static_cast<std::size_t>(k)], 0.0f};
    forward->execute();
    std::vector<std::complex<float>> spectrum(static_cast<std::size_t>(nf));
    for (int k = 0; k < nf; ++k) spectrum[static_cast<std::size_t>(k)] = std::conj(out.c()[k]);
    return spectrum;
  }

  /// Block b less its mean (ADC offsets), mixed by IF + f, stretched to nf samples, into `in`.
  void mix_block(std::span<const Sample> x, int b, double f_hz, std::vector<std::complex<float>>& scratch) {
    const std::int64_t first = static_cast<std::int64_t>(b) * n;
    std::complex<double> dc = 0.0;
    for (int k = 0; k < n; ++k) {
      const auto& s = x[static_cast<std::size_t>(first + k)];
      dc += std::complex<double>(s.real(), s.imag());
    }
    const std::complex<float> mean(dc / static_cast<double>(n));
    const double w = -2.0 * M_PI * (cfg.if_hz + f_hz) / cfg.sample_rate_hz;
    std::complex<double> rot = std::polar(1.0, w * static_cast<double>(first));
    const std::complex<double> step = std::polar(1.0, w);
    std::complex<float>* dst = nf == n ? in.c() : scratch.data();
    for (int k = 0; k < n; ++k) {
      const auto& s = x[static_cast<std::size_t>(first + k)];
      dst[k] = (std::complex<float>(static_cast<float>(s.real()), static_cast<float>(s.imag())) - mean) *
               std::complex<float>(rot);
      rot *= step;
      if ((k & 1023) == 1023) rot /= std::abs(rot);  // keep the recursion on the unit circle
    }
    if (nf != n)
      for (int j = 0; j < nf; ++j)
        in.c()[j] = scratch[static_cast<std::size_t>(stretch_source[static_cast<std::size_t>(j)])];
  }

  std::vector<std::complex<float>> scratch;
  std::vector<std::vector<std::complex<float>>> block_spectra;
  std::vector<float> row;
  std::vector<GridSummary> summaries;

  std::vector<GalileoAcquisitionResult> search(std::span<const Sample> x, const std::vector<int>& prns) {
    for (int p : prns)
      if (std::find(cfg.prns.begin(), cfg.prns.end(), p) == cfg.prns.end())
        throw std::invalid_argument(fmt::format("Galileo acquisition: E{:02d} is not among the SVIDs configured", p));
    const int blocks =
        static_cast<int>(std::min<std::int64_t>(cfg.noncoherent, static_cast<std::int64_t>(x.size()) / n));
    if (blocks < 1)
      throw std::invalid_argument(
          fmt::format("Galileo acquisition: need at least {} samples (one 4 ms code period), got {}", n, x.size()));
    scratch.resize(static_cast<std::size_t>(n));
    block_spectra.resize(static_cast<std::size_t>(blocks));
    for (auto& s : block_spectra) s.resize(static_cast<std::size_t>(nf));
    row.resize(static_cast<std::size_t>(nf));
    summaries.resize(prns.size());
    for (auto& s : summaries) s.reset(nf);
    for (std::size_t d = 0; d < dopplers.size(); ++d) {
      for (int b = 0; b < blocks; ++b) {
        mix_block(x, b, dopplers[d], scratch);
        forward->execute();
        std::copy(out.c(), out.c() + nf, block_spectra[static_cast<std::size_t>(b)].begin());
      }
      for (std::size_t p = 0; p < prns.size(); ++p) {
        std::fill(row.begin(), row.end(), 0.0f);
        for (const auto* codes : {&spectra_b, &spectra_c}) {
          const auto& code = (*codes)[static_cast<std::size_t>(prns[p] - 1)];
          for (int b = 0; b < blocks; ++b) {
            multiply_spectra(block_spectra[static_cast<std::size_t>(b)].data(), code.data(), in.c(), nf);
            inverse->execute();
            add_power(out.c(), row.data(), nf);
          }
        }
        summaries[p].add_row(row, d);
      }
    }
    const int terms = 2 * blocks;  // |B|^2 and |C|^2 of each block
    const double cells = static_cast<double>(dopplers.size()) * std::floor(samples_per_period);
    const double threshold = acquisition_threshold(terms, cells, cfg.pfa);
    const std::span<const Sample> searched = x.first(static_cast<std::size_t>(blocks) * static_cast<std::size_t>(n));
    std::vector<GalileoAcquisitionResult> results;
    for (std::size_t p = 0; p < prns.size(); ++p)
      results.push_back(evaluate(searched, prns[p], summaries[p], terms, threshold));
    acquisition_kernels::reject_cross_correlations(results, cfg.cross_correlation_margin_db);
    return results;
  }

  /// Mean cell away from the peak's lag (modulo a code period), over all Doppler bins.
  double noise_floor(const GridSummary& s) const {
    const double lags_per_period = samples_per_period * nf / n;
    const double exclusion = kPeakExclusion_chips * lags_per_period / kE1CodeLength_chips;
    double sum = 0.0, count = 0.0;
    for (int k = 0; k < nf; ++k) {
      double off = std::fmod(std::abs(static_cast<double>(k - s.peak_lag)), lags_per_period);
      off = std::min(off, lags_per_period - off);
      if (off <= exclusion) continue;
      sum += s.lag_sums[static_cast<std::size_t>(k)];
      count += 1.0;
    }
    count *= static_cast<double>(dopplers.size());
    return count > 0 ? sum / count : 1.0;
  }

  double delay_from_code_phase(double code_phase_chips) const {
    const double delay = (kE1CodeLength_chips - code_phase_chips) * cfg.sample_rate_hz / kE1CodeRate_cps;
    return std::fmod(delay, samples_per_period);
  }

  GalileoAcquisitionResult evaluate(std::span<const Sample> x, int prn, const GridSummary& s, int terms,
                                    double threshold) const {
    const double cell_mean = noise_floor(s);
    GalileoAcquisitionResult r;
    r.satellite = {GnssSystem::galileo, prn};
    r.threshold = threshold;
    r.statistic = s.peak / (cell_mean / terms);
    r.detected = r.statistic > threshold;
    // The grid's lag (in units of n / nf samples) as a delay, and the code phase it implies.
    const double coarse_delay = std::fmod(s.peak_lag * static_cast<double>(n) / nf, samples_per_period);
    const double coarse_phase =
        std::fmod(kE1CodeLength_chips - coarse_delay * kE1CodeRate_cps / cfg.sample_rate_hz + kE1CodeLength_chips,
                  static_cast<double>(kE1CodeLength_chips));
    const double t_coh = galileo::kE1CodePeriod_s;
    if (!r.detected) {
      r.doppler_hz = dopplers[s.peak_bin];
      r.delay_samples = coarse_delay;
      r.code_phase_chips = coarse_phase;
      // Peak-to-floor ratio, less the stretch's repeated samples (nf / n), per component:
      // each holds half the signal.
      const double snr = (s.peak / cell_mean - 1.0) * n / nf;
      r.cn0_dbhz = snr > 0.0 ? 10.0 * std::log10(2.0 * snr / t_coh) : 0.0;
      return r;
    }
    const E1RefinedSignal refined = refiner.refine(x, prn, coarse_phase, dopplers[s.peak_bin], cfg.doppler_step_hz);
    r.doppler_hz = refined.doppler_hz;
    r.code_phase_chips = refined.code_phase_chips;
    r.delay_samples = delay_from_code_phase(refined.code_phase_chips);
    r.moved_off_side_lobe = refined.moved_off_side_lobe;
    // C/N0: a grid cell's noise per component and block is cell_mean / (2K) in the grid's units,
    // nf^3 / n times that of a direct correlation over n samples (acquisition.cpp). Signal:
    // the refined power per component and whole code period (all periods when the samples
    // hold no whole one).
    const double noise = cell_mean / terms * n / (static_cast<double>(nf) * nf * nf);
    const bool whole = refined.power.full_period_count > 0;
    const double per_component = whole ? refined.power.full_periods / (2.0 * refined.power.full_period_count)
                                       : refined.power.all_periods / (2.0 * static_cast<double>(x.size()) / n);
    const double snr = (per_component - noise) / noise;
    r.cn0_dbhz = snr > 0.0 ? 10.0 * std::log10(2.0 * snr / t_coh) : 0.0;
    return r;
  }
};

GalileoAcquisition::GalileoAcquisition(GalileoAcquisitionConfig config)
    : impl_(std::make_unique<Impl>(std::move(config))) {}
GalileoAcquisition::~GalileoAcquisition() = default;

std::int64_t GalileoAcquisition::samples_needed() const {
  return static_cast<std::int64_t>(impl_->n) * impl_->cfg.noncoherent;
}

std::vector<GalileoAcquisitionResult> GalileoAcquisition::search(std::span<const Sample> samples) {
  return impl_->search(samples, impl_->cfg.prns);
}

std::vector<GalileoAcquisitionResult> GalileoAcquisition::search(std::span<const Sample> samples,
                                                                 const std::vector<int>& prns) {
  return impl_->search(samples, prns);
}

}  // namespace deepnav
