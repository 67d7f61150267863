#pragma once
// Pulse blanking: a sample whose power stands above the noise estimate by the threshold
// marks a pulse; it and `guard` samples on each side are set to zero (the correlators
// then integrate only the clean part of each period, losing the duty cycle's share of
// signal instead of drowning in the pulse). The noise estimate is a running mean of the
// power of unblanked samples, started from the median of the first samples so a pulse in
// them does not inflate it. Samples that are not blanked pass bit-exact.
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "receiver/mitigation/mitigation_config.hpp"
#include "receiver/mitigation/mitigation_stage.hpp"

namespace deepnav {

class PulseBlanker final : public MitigationStage {
 public:
  /// Validates the configuration (std::invalid_argument naming the field).
  PulseBlanker(const MitigationConfig& config, double sample_rate_hz);

  /// The guard interval: a pulse's leading edge is zeroed before the detection.
  std::size_t delay_samples() const override { return guard_; }
  void process(std::span<const std::complex<float>> in, std::span<std::complex<float>> out) override;
  void reset() override;

  /// Samples zeroed over samples seen so far.
  double blanked_fraction() const;
  /// Per-sample noise power estimate (input units squared); < 0 before the first sample.
  double noise_power() const { return noise_power_; }

 private:
  void initialize_noise(std::span<const std::complex<float>> in);

  std::size_t guard_;
  double threshold_ratio_, alpha_;
  double noise_power_ = -1.0;
  std::vector<std::complex<float>> delay_line_;  ///< the last guard_ inputs, circular
  std::size_t delay_pos_ = 0;
  std::int64_t position_ = 0;     ///< inputs seen since the last reset
  std::int64_t zero_until_ = -1;  ///< outputs up to this input position are zeroed
  std::int64_t seen_ = 0, blanked_ = 0;
};

}  // namespace deepnav
