#include "receiver/acquisition/signal_diagnostics.hpp"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <complex>
#include <limits>

#include "receiver/acquisition/fftw_plan.hpp"

namespace deepnav {
namespace {

/// Averaging more segments than this gains nothing a diagnosis needs (the bins' scatter
/// is then about 0.2 dB) and would only cost time on a long window.
constexpr std::size_t kMaxSegments = 400;
/// Bins of the boxcar that smooths the periodogram before its band is looked for.
constexpr int kSmoothingBins = 5;
/// A band must rise this far (dB) over the floor: white noise, averaged over tens of
/// segments and smoothed, scatters by a fraction of a dB.
constexpr double kMinContrast_db = 3.0;

double decibels(double power) {
  return power > 0.0 ? 10.0 * std::log10(power) : -std::numeric_limits<double>::infinity();
}

/// The averaged power per bin, in frequency order: bin j is (j - L/2) fs / L.
std::vector<double> averaged_periodogram(std::span<const Sample> samples, std::size_t segments) {
  constexpr int L = kSpectrumSegment;
  std::complex<double> mean = 0.0;
  for (const Sample& s : samples) mean += std::complex<double>(s.real(), s.imag());
  mean /= static_cast<double>(samples.size());
  std::vector<std::complex<float>> buffer(L);
  auto* fftw = reinterpret_cast<fftwf_complex*>(buffer.data());
  const FftwPlan forward(L, fftw, fftw, FFTW_FORWARD);
  std::vector<double> window(L), power(L, 0.0);
  for (int k = 0; k < L; ++k) window[static_cast<std::size_t>(k)] = 0.5 - 0.5 * std::cos(2.0 * M_PI * k / L);
  // Segments spread over the whole span, so a long window is sampled end to end.
  const std::size_t stride = samples.size() / L / segments * L;
  for (std::size_t seg = 0; seg < segments; ++seg) {
    const Sample* x = samples.data() + seg * stride;
    for (int k = 0; k < L; ++k) {
      const auto u = static_cast<std::size_t>(k);
      buffer[u] = std::complex<float>((std::complex<double>(x[k].real(), x[k].imag()) - mean) * window[u]);
    }
    forward.execute();
    for (int k = 0; k < L; ++k) power[static_cast<std::size_t>((k + L / 2) % L)] += std::norm(buffer[k]);
  }
  return power;
}

/// Boxcar over kSmoothingBins, in dB; `circular` wraps at the ends (a complex spectrum).
std::vector<double> smoothed_db(const std::vector<double>& power, bool circular) {
  const int n = static_cast<int>(power.size());
  std::vector<double> out(power.size());
  for (int j = 0; j < n; ++j) {
    double sum = 0.0;
    int count = 0;
    for (int d = -kSmoothingBins / 2; d <= kSmoothingBins / 2; ++d) {
      int k = j + d;
      if (circular) k = (k + n) % n;
      if (k < 0 || k >= n) continue;
      sum += power[static_cast<std::size_t>(k)];
      ++count;
    }
    out[static_cast<std::size_t>(j)] = decibels(sum / count);
  }
  return out;
}

double percentile(std::vector<double> values, double p) {
  const auto at = static_cast<std::ptrdiff_t>(std::floor(p * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + at, values.end());
  return values[static_cast<std::size_t>(at)];
}

/// Walks from bin `peak` in direction `step` while the level stays at or above `level`; the
/// edge, in fractional bins from `peak`, lies where the level is crossed (interpolated), or
/// at the end of a non-circular spectrum. nullopt when the walk goes all the way round.
std::optional<double> band_edge(const std::vector<double>& db, int peak, int step, double level, bool circular) {
  const int n = static_cast<int>(db.size());
  for (int walked = 1; walked < n; ++walked) {
    const int k = peak + step * walked;
    if (!circular && (k < 0 || k >= n)) return step * (walked - 1);
    const double inside = db[static_cast<std::size_t>((k - step + n) % n)];
    const double outside = db[static_cast<std::size_t>((k + n) % n)];
    if (outside < level) return step * (walked - 1 + (inside - level) / (inside - outside));
  }
  return std::nullopt;
}

}  // namespace

SampleLevels measure_levels(std::span<const Sample> samples, bool real, SampleValueRange range) {
  SampleLevels out;
  out.samples = samples.size();
  if (samples.empty()) return out;
  std::bitset<65536> values, low_bytes;
  const int rail = std::min(-range.min, range.max);
  double sum_i = 0.0, sum_q = 0.0;
  std::size_t at_rail = 0;
  const auto tally = [&](int v) {
    values.set(static_cast<std::size_t>(v + 32768));
    low_bytes.set(static_cast<std::size_t>(v & 0xff));
    at_rail += std::abs(v) >= rail ? 1 : 0;
  };
  for (const Sample& s : samples) {
    sum_i += static_cast<double>(s.real()) * s.real();
    sum_q += static_cast<double>(s.imag()) * s.imag();
    tally(s.real());
    if (!real) tally(s.imag());
  }
  const auto n = static_cast<double>(samples.size());
  const int components = real ? 1 : 2;
  out.rms_i = std::sqrt(sum_i / n);
  out.rms_q = std::sqrt(sum_q / n);
  const double full_scale = 0.5 * (range.max - range.min);
  out.power_dbfs = decibels((sum_i + sum_q) / (n * components) / (full_scale * full_scale));
  out.at_full_scale_fraction = static_cast<double>(at_rail) / (n * components);
  out.levels_used = static_cast<int>(values.count());
  out.low_byte_levels = static_cast<int>(low_bytes.count());
  if (!real) out.iq_power_ratio_db = decibels(sum_i) - decibels(sum_q);
  return out;
}

SpectrumBand find_spectrum_band(std::span<const Sample> samples, double sample_rate_hz, bool real) {
  SpectrumBand band;
  band.resolution_hz = sample_rate_hz / kSpectrumSegment;
  // Fewer than 8 segments scatter by a dB or more: no band could be told from that.
  const std::size_t segments = std::min(kMaxSegments, samples.size() / kSpectrumSegment);
  if (segments < 8) return band;
  std::vector<double> power = averaged_periodogram(samples, segments);
  // Real samples: their spectrum is mirrored about 0; look at [0, fs/2) only.
  if (real) power.erase(power.begin(), power.begin() + kSpectrumSegment / 2);
  const std::vector<double> db = smoothed_db(power, !real);
  const double floor_db = percentile(db, 0.1), top_db = percentile(db, 0.9);
  band.contrast_db = top_db - floor_db;
  if (!(band.contrast_db >= kMinContrast_db)) return band;
  const double level = 0.5 * (floor_db + top_db);
  const int peak = static_cast<int>(std::distance(db.begin(), std::max_element(db.begin(), db.end())));
  const auto low = band_edge(db, peak, -1, level, !real), high = band_edge(db, peak, +1, level, !real);
  if (!low || !high) return band;
  // Bin j of the kept bins is at (j + origin) resolution Hz.
  const double origin = real ? 0.0 : -kSpectrumSegment / 2.0;
  double centre = (peak + 0.5 * (*low + *high) + origin) * band.resolution_hz;
  if (!real) centre = std::remainder(centre, sample_rate_hz);  // a band across +-fs/2 wraps
  band.found = true;
  band.centre_hz = centre;
  band.width_hz = (*high - *low) * band.resolution_hz;
  return band;
}

double threshold_ratio(const AcquisitionResult& result) {
  return result.threshold > 0.0 ? result.statistic / result.threshold : 0.0;
}

std::optional<AcquisitionResult> strongest_correlation(const std::vector<AcquisitionResult>& results) {
  const auto best = std::max_element(results.begin(), results.end(), [](const auto& a, const auto& b) {
    return threshold_ratio(a) < threshold_ratio(b);
  });
  if (best == results.end()) return std::nullopt;
  return *best;
}

}  // namespace deepnav
