#pragma once
// Test signals for the interference-mitigation tests: a C/A signal in white noise with an
// optional jammer from the synthesizer, quantised to int16 as a source delivers it, a
// vector-backed SampleSource (with an optional gap), and the 1 ms correlation SNR the
// receiver's prompt correlator would see.
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "signals/ca_code.hpp"
#include "signals/sim/jammer.hpp"

namespace deepnav::test {

inline constexpr double kFs = 4.092e6;
inline constexpr double kCn0Dbhz = 45.0;
inline constexpr int kPrn = 7;
inline constexpr double kDopplerHz = 1200.0;
/// Int16 units per sqrt(N0): complex noise of density 1 has per-component sigma
/// sqrt(fs/2) = 1430; scaled to sigma 64, the loading of an 8-bit converter.
inline const double kScale = 64.0 / std::sqrt(kFs / 2.0);

/// Clean replica (unit amplitude) of the test satellite at sample k.
inline std::complex<double> replica(std::int64_t k) {
  const auto& chips = ca_code_chips(kPrn);
  const double t = static_cast<double>(k) / kFs;
  const auto chip = static_cast<std::size_t>(std::fmod(t * 1.023e6, 1023.0));
  return static_cast<double>(chips[chip]) * std::polar(1.0, 2.0 * std::numbers::pi * kDopplerHz * t);
}

/// n samples of satellite + noise (+ jammer), in int16 units (see kScale).
inline std::vector<Sample> test_samples(std::size_t n, std::optional<JammerConfig> jammer, bool with_noise = true,
                                        std::uint32_t seed = 11) {
  std::vector<std::complex<float>> x(n);
  const double amplitude = std::sqrt(std::pow(10.0, kCn0Dbhz / 10.0));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, std::sqrt(kFs / 2.0));
  for (std::size_t k = 0; k < n; ++k) {
    std::complex<double> v = amplitude * replica(static_cast<std::int64_t>(k));
    if (with_noise) v += std::complex<double>(normal(rng), normal(rng));
    x[k] = std::complex<float>(v);
  }
  if (jammer) Jammer(*jammer, kFs, 0.0, kCn0Dbhz, seed).add_to(x, 0);
  std::vector<Sample> out(n);
  for (std::size_t k = 0; k < n; ++k)
    out[k] = Sample(static_cast<std::int16_t>(std::lround(x[k].real() * kScale)),
                    static_cast<std::int16_t>(std::lround(x[k].imag() * kScale)));
  return out;
}

/// Coherent SNR (dB) of 1 ms prompt correlations with the test satellite: |mean|^2 / variance.
inline double correlation_snr_db(const std::vector<Sample>& y, std::size_t first = 0) {
  const auto len = static_cast<std::size_t>(kFs / 1000.0);
  std::vector<std::complex<double>> sums;
  for (std::size_t k0 = first; k0 + len <= y.size(); k0 += len) {
    std::complex<double> acc = 0;
    for (std::size_t k = k0; k < k0 + len; ++k)
      acc += std::complex<double>(y[k].real(), y[k].imag()) * std::conj(replica(static_cast<std::int64_t>(k)));
    sums.push_back(acc);
  }
  std::complex<double> mean = 0;
  for (auto v : sums) mean += v / static_cast<double>(sums.size());
  double var = 0;
  for (auto v : sums) var += std::norm(v - mean) / static_cast<double>(sums.size() - 1);
  return 10.0 * std::log10(std::norm(mean) / var);
}

/// Power (int16 units squared) of the component of y at a frequency: |mean(y e^{-j w k})|^2.
inline double tone_power(const std::vector<Sample>& y, double freq_hz, std::size_t first = 0) {
  std::complex<double> acc = 0;
  for (std::size_t k = first; k < y.size(); ++k)
    acc += std::complex<double>(y[k].real(), y[k].imag()) *
           std::polar(1.0, -2.0 * std::numbers::pi * freq_hz * static_cast<double>(k) / kFs);
  return std::norm(acc / static_cast<double>(y.size() - first));
}

/// Serves a vector in reads of at most `piece` samples; samples at [gap_at, gap_at + gap)
/// are never delivered and reported as a gap, like a dropped network packet.
class VectorSampleSource final : public SampleSource {
 public:
  VectorSampleSource(std::vector<Sample> samples, std::size_t piece, std::size_t gap_at = 0, std::size_t gap = 0)
      : samples_(std::move(samples)), piece_(piece), gap_at_(gap_at), gap_(gap) {}
  double sample_rate_hz() const override { return kFs; }
  double intermediate_frequency_hz() const override { return 0.0; }
  bool is_real() const override { return false; }
  std::size_t read(std::span<Sample> out) override {
    if (gap_ > 0 && next_ == gap_at_) {
      report_gap({static_cast<std::int64_t>(gap_at_), static_cast<std::int64_t>(gap_)});
      next_ += gap_;
    }
    std::size_t end = std::min(samples_.size(), next_ + std::min(piece_, out.size()));
    if (gap_ > 0 && next_ < gap_at_) end = std::min(end, gap_at_);
    const std::size_t n = end > next_ ? end - next_ : 0;
    std::copy_n(samples_.begin() + static_cast<std::ptrdiff_t>(next_), n, out.begin());
    next_ += n;
    at_end_ = n == 0;
    return n;
  }
  std::int64_t next_sample_index() const override { return static_cast<std::int64_t>(next_); }
  bool at_end() const override { return at_end_; }

 private:
  std::vector<Sample> samples_;
  std::size_t piece_, gap_at_, gap_;
  std::size_t next_ = 0;
  bool at_end_ = false;
};

/// Reads a source to its end in reads of `piece`: samples by absolute index (never
/// delivered ones stay zero) and the number of samples delivered.
struct Drained {
  std::vector<Sample> by_index;
  std::size_t delivered = 0;
  std::vector<SampleGap> gaps;
};
inline Drained drain(SampleSource& source, std::size_t total, std::size_t piece) {
  Drained d;
  d.by_index.assign(total, Sample(0, 0));
  source.set_gap_handler([&](const SampleGap& g) { d.gaps.push_back(g); });
  std::vector<Sample> buf(piece);
  while (const std::size_t n = source.read(buf)) {
    const std::int64_t first = source.next_sample_index() - static_cast<std::int64_t>(n);
    for (std::size_t k = 0; k < n; ++k) d.by_index.at(static_cast<std::size_t>(first) + k) = buf[k];
    d.delivered += n;
  }
  return d;
}

}  // namespace deepnav::test
