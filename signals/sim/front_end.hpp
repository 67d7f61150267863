#pragma once
// The synthesizer's front end: takes a block of the summed satellite signals at IF
// (complex analytic samples), adds the jammers and thermal noise, runs the AGC and the
// ADC, and packs the result in the output sample format.
//
// Power convention (thermal noise density N0 = 1): a satellite at C/N0 = c dB-Hz has
// complex amplitude sqrt(10^(c/10)); complex noise has variance fs (fs/2 per component).
// Jammers: see jammer.hpp (J = C_ref 10^(J/S / 10)).
// Real output (format byte): the real sample is sqrt(2) Re{x} plus real noise of
// variance N0 fs / 2. The sqrt(2) keeps every component's power: a complex tone of power
// C becomes a real sinusoid sqrt(2C) cos(.) of power C, so C/N0 and J/N0 are the same in
// real and complex outputs and the caller passes the same complex block for both.
#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "signals/sample_format.hpp"
#include "signals/sim/adc.hpp"
#include "signals/sim/indexed_noise.hpp"
#include "signals/sim/jammer.hpp"

namespace deepnav {

struct FrontEndConfig {
  double sample_rate_hz = 4.092e6;
  double if_hz = 0.0;
  SampleFormat format = SampleFormat::ibyte;
  AdcConfig adc;
  double cn0_ref_dbhz = 45.0;  ///< nominal satellite C/N0 that the jammers' J/S refers to
  std::vector<JammerConfig> jammers;
  bool thermal_noise = true;  ///< false: no noise (tests, noise-free references)
};

class FrontEnd {
 public:
  /// Validates everything (throws std::invalid_argument naming the field, e.g.
  /// "jammers[1]: jammer js_db = ..."). The seed drives the thermal noise and, through
  /// derived seeds, each jammer's noise.
  /// `threads`: workers for the thermal noise (its values depend only on the sample index,
  /// so the samples are the same for any count).
  FrontEnd(FrontEndConfig config, std::uint64_t seed, unsigned threads = 1);

  /// block: signals at IF for samples [first_sample, first_sample + block.size()); the
  /// block is modified in place (jammers added). out_bytes is resized to the block's bytes
  /// in `format` and filled (a packed format needs blocks of whole words). Blocks must be contiguous for
  /// the AGC state to evolve as in hardware; noise and jammers depend only on the index.
  void process(std::span<std::complex<float>> block, std::int64_t first_sample, std::vector<std::byte>& out_bytes);

  const FrontEndConfig& config() const { return config_; }
  const Agc& agc() const { return agc_; }

 private:
  /// AGC + quantizer over n values (interleaved complex or real), windows aligned to samples.
  void digitize(const float* x, std::size_t n_samples, int values_per_sample, std::int64_t first_sample,
                std::byte* out);

  /// Thermal noise on the block, split across the workers at the noise generator's chunk
  /// boundaries (where a generator starts without skipping draws).
  void add_thermal_noise(std::span<std::complex<float>> block, std::int64_t first_sample);

  FrontEndConfig config_;
  float noise_sigma_;
  unsigned threads_;
  /// One generator per worker; a worker takes the one that left off where its range starts
  /// (a generator sent elsewhere in its chunk would skip draws to get there).
  std::vector<IndexedNoise> noise_;
  std::vector<Jammer> jammers_;
  Agc agc_;
  std::vector<float> real_;           ///< real-output scratch
  std::vector<std::int16_t> levels_;  ///< packed output: the block's levels before packing
};

}  // namespace deepnav
