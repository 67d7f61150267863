#pragma once
// Measurements of IF samples that tell why an acquisition found nothing: how the samples
// use the converter's range (power, levels, values at full scale, I/Q balance), where the
// spectrum's band lies (a front end's filter centres it on the IF), and which correlation
// came nearest the detection threshold. One pass and a few hundred short FFTs over some ms
// of samples: cheap enough to make whenever a search comes back empty.
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "receiver/acquisition/acquisition.hpp"
#include "receiver/sources/sample_converter.hpp"
#include "receiver/sources/sample_source.hpp"

namespace deepnav {

/// How the samples fill the range of the values they were read as.
struct SampleLevels {
  std::size_t samples = 0;
  double rms_i = 0.0, rms_q = 0.0;  ///< per component, in converted units (Q: 0 for real samples)
  /// Mean power of the components against a full-scale value on every one (0 dBFS: every
  /// value at full scale), -inf for silence.
  double power_dbfs = 0.0;
  double at_full_scale_fraction = 0.0;  ///< of the values, those at either end of the range (the rails)
  int levels_used = 0;                  ///< distinct values among the components
  /// Distinct low bytes of the values (16-bit containers): a handful while the values
  /// spread over thousands of levels means pairs of 8-bit values read as one 16-bit value.
  int low_byte_levels = 0;
  /// I over Q power (dB) for complex samples; 0 for real ones.
  double iq_power_ratio_db = 0.0;
};

/// `range`: the values the sample format's samples convert to (full scale: half its span).
SampleLevels measure_levels(std::span<const Sample> samples, bool real, SampleValueRange range);

/// The band the spectrum rises over, found from an averaged periodogram: the band's edges
/// are where the smoothed power crosses halfway (in dB) between the floor (10th percentile
/// of the bins) and the top (90th percentile), on either side of the strongest bin.
struct SpectrumBand {
  /// False for a spectrum without a band (white noise: contrast under 3 dB) or too few samples.
  bool found = false;
  /// The midpoint of the band's edges, in the samples' frequency: (-fs/2, fs/2] for
  /// complex samples, [0, fs/2] for real ones (whose spectrum is mirrored about 0).
  double centre_hz = 0.0;
  double width_hz = 0.0;
  double contrast_db = 0.0;  ///< top over floor
  double resolution_hz = 0.0;
};

/// Periodogram segments of this many samples (fs / 256 per bin: about 16 kHz at 4 Msps).
inline constexpr int kSpectrumSegment = 256;

SpectrumBand find_spectrum_band(std::span<const Sample> samples, double sample_rate_hz, bool real);

/// What a receiver's acquisition saw: the configuration it searched with, the latest
/// samples it kept (up to one search's worth) and the correlation nearest the threshold of
/// every search made.
struct AcquisitionEvidence {
  AcquisitionConfig config;
  std::vector<Sample> samples;
  std::optional<AcquisitionResult> strongest;
};

/// The result whose statistic came nearest its threshold (detected or not), none when
/// `results` is empty.
std::optional<AcquisitionResult> strongest_correlation(const std::vector<AcquisitionResult>& results);
/// statistic / threshold: 1 at the detection threshold.
double threshold_ratio(const AcquisitionResult& result);

}  // namespace deepnav
