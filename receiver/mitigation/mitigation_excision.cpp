#include "receiver/mitigation/mitigation_excision.hpp"

#include <fftw3.h>

#include "receiver/acquisition/fftw_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace deepnav {

struct FrequencyExcision::Fft {
  explicit Fft(std::size_t n)
      : buffer(allocate(n)),
        forward(static_cast<int>(n), buffer, buffer, FFTW_FORWARD),
        inverse(static_cast<int>(n), buffer, buffer, FFTW_BACKWARD) {}
  ~Fft() { fftwf_free(buffer); }
  Fft(const Fft&) = delete;
  Fft& operator=(const Fft&) = delete;
  std::complex<float>* data() { return reinterpret_cast<std::complex<float>*>(buffer); }

  static fftwf_complex* allocate(std::size_t n) {
    fftwf_complex* b = fftwf_alloc_complex(n);
    if (b == nullptr) throw std::runtime_error("excision: FFTW could not allocate its buffer");
    return b;
  }
  fftwf_complex* buffer;
  FftwPlan forward, inverse;
};

FrequencyExcision::FrequencyExcision(const MitigationConfig& config, double sample_rate_hz) {
  validate_mitigation(config, sample_rate_hz);
  fft_size_ = static_cast<std::size_t>(config.excision_fft_size);
  hop_ = fft_size_ / 2;
  // Median of an exponential variable is ln 2 times its mean.
  threshold_over_median_ = static_cast<float>(std::pow(10.0, config.excision_threshold_db / 10.0) / std::numbers::ln2);
  window_.resize(fft_size_);
  for (std::size_t n = 0; n < fft_size_; ++n)  // periodic Hann: shifted copies by N/2 sum to exactly 1
    window_[n] = static_cast<float>(
        0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(n) / static_cast<double>(fft_size_)));
  power_.resize(fft_size_);
  fft_ = std::make_unique<Fft>(fft_size_);
  reset();
}

FrequencyExcision::~FrequencyExcision() = default;

void FrequencyExcision::reset() {
  history_.assign(fft_size_, {});
  overlap_.assign(fft_size_, {});
  new_inputs_ = 0;
  // One hop of zeros ahead of the first frame's output keeps the output exactly one
  // frame behind the input whatever the block sizes.
  ready_.assign(hop_, {});
  ready_pos_ = 0;
}

void FrequencyExcision::process(std::span<const std::complex<float>> in, std::span<std::complex<float>> out) {
  for (std::size_t k = 0; k < in.size(); ++k) {
    const std::complex<float> x = in[k];  // read before out[k] is written (in and out may alias)
    history_[hop_ + new_inputs_] = x;
    if (++new_inputs_ == hop_) run_frame();
    out[k] = ready_[ready_pos_++];
  }
}

void FrequencyExcision::run_frame() {
  std::complex<float>* X = fft_->data();
  for (std::size_t n = 0; n < fft_size_; ++n) X[n] = history_[n] * window_[n];
  fft_->forward.execute();
  for (std::size_t k = 0; k < fft_size_; ++k) power_[k] = std::norm(X[k]);
  std::vector<float>& sorted = power_;  // reordered by nth_element: recompute powers below
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(fft_size_ / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  const float limit = *mid * threshold_over_median_;
  std::int64_t excised = 0;
  for (std::size_t k = 0; k < fft_size_; ++k) {
    if (std::norm(X[k]) > limit) {
      X[k] = 0.0f;
      ++excised;
    }
  }
  bins_examined_ += static_cast<std::int64_t>(fft_size_);
  bins_excised_ += excised;
  fft_->inverse.execute();
  const float scale = 1.0f / static_cast<float>(fft_size_);
  for (std::size_t n = 0; n < fft_size_; ++n) overlap_[n] += X[n] * scale;
  // The first half now has both frames that cover it: hand it out and slide by a hop.
  ready_.erase(ready_.begin(), ready_.begin() + static_cast<std::ptrdiff_t>(ready_pos_));
  ready_pos_ = 0;
  ready_.insert(ready_.end(), overlap_.begin(), overlap_.begin() + static_cast<std::ptrdiff_t>(hop_));
  std::copy(overlap_.begin() + static_cast<std::ptrdiff_t>(hop_), overlap_.end(), overlap_.begin());
  std::fill(overlap_.begin() + static_cast<std::ptrdiff_t>(hop_), overlap_.end(), std::complex<float>{});
  std::copy(history_.begin() + static_cast<std::ptrdiff_t>(hop_), history_.end(), history_.begin());
  new_inputs_ = 0;
}

double FrequencyExcision::excised_bin_fraction() const {
  return bins_examined_ == 0 ? 0.0 : static_cast<double>(bins_excised_) / static_cast<double>(bins_examined_);
}

}  // namespace deepnav
