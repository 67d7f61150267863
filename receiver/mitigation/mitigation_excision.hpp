#pragma once
// Frequency-domain excision: short-time Fourier frames (Hann window, half overlap, so
// the windows sum to one and a clean signal is rebuilt exactly) in which every bin
// whose power stands above the frame's noise floor by the threshold is zeroed. The
// noise floor comes from the median bin power (median = ln 2 x mean for noise), which a
// narrowband interferer occupying under half of the band does not move. A GPS signal
// is far below the noise in every bin and is never excised; a CW or a chirp that
// sweeps only a few bins per frame is. FFTW plans are made once, in the constructor.
#include <complex>
#include <cstdint>
#include <memory>
#include <vector>

#include "receiver/mitigation/mitigation_config.hpp"
#include "receiver/mitigation/mitigation_stage.hpp"

namespace deepnav {

class FrequencyExcision final : public MitigationStage {
 public:
  /// Validates the configuration (std::invalid_argument naming the field).
  FrequencyExcision(const MitigationConfig& config, double sample_rate_hz);
  ~FrequencyExcision() override;
  FrequencyExcision(const FrequencyExcision&) = delete;
  FrequencyExcision& operator=(const FrequencyExcision&) = delete;

  /// One FFT length: the frame hop is half of it and the output lags by a whole frame.
  std::size_t delay_samples() const override { return fft_size_; }
  void process(std::span<const std::complex<float>> in, std::span<std::complex<float>> out) override;
  void reset() override;

  /// Bins zeroed over bins examined so far (for reports and tests).
  double excised_bin_fraction() const;

 private:
  void run_frame();

  std::size_t fft_size_, hop_;
  float threshold_over_median_;
  std::vector<float> window_;
  std::vector<std::complex<float>> history_;  ///< the last fft_size_ inputs
  std::size_t new_inputs_ = 0;                ///< inputs since the last frame
  std::vector<std::complex<float>> overlap_;  ///< overlap-add accumulator, fft_size_
  std::vector<std::complex<float>> ready_;    ///< finished outputs not yet handed out
  std::size_t ready_pos_ = 0;
  std::vector<float> power_;
  std::int64_t bins_examined_ = 0, bins_excised_ = 0;
  struct Fft;
  std::unique_ptr<Fft> fft_;
};

}  // namespace deepnav
