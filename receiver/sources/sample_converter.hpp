#pragma once
// Raw IF bytes of a sample format -> the receiver's complex int16 samples, exactly as
// FileSampleSource converts a file (same rounding, saturation, spectrum inversion and
// gr_complex scaling), so a stream and a file of the same bytes give the same samples.
// cu8 (unsigned, zero at 127.5) becomes 2u - 255: twice the offset value, so it stays an
// integer and keeps the odd, zero-free level set an 8-bit ADC has. Packed formats give
// their quantizer levels (signals/sample_packing.hpp): 2 bits {-3, -1, 1, 3}.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "signals/sample_format.hpp"

namespace deepnav {

/// The least and greatest value a component of `format` converts to (before spectrum
/// inversion): int8 formats -128..127, int16 and gr_complex (saturated) -32768..32767, cu8
/// -255..255, packed B bits -(2^B - 1)..2^B - 1.
struct SampleValueRange {
  int min = 0, max = 0;
};
SampleValueRange converted_value_range(const SampleFormat& format);

class SampleConverter {
 public:
  /// gr_complex values are scaled so the RMS of the first kCalibrationSamples lands at
  /// 2048 (24 dB below int16 full scale), as FileSampleSource does.
  static constexpr std::size_t kCalibrationSamples = 1 << 16;

  SampleConverter(SampleFormat format, bool inverted_spectrum);

  /// Sets the gr_complex scale from the first samples of the stream (no-op for the
  /// integer formats); convert() before this uses unit scale.
  void calibrate(std::span<const std::byte> first_samples);
  bool needs_calibration() const { return format_ == SampleFormat::gr_complex && !calibrated_; }

  /// Converts the whole samples of raw (whole words of a packed format) into out (which
  /// must hold them);
  /// `first_index` only names a non-finite gr_complex sample in the error it throws.
  void convert(std::span<const std::byte> raw, std::span<Sample> out, std::int64_t first_index) const;

  SampleFormat format() const { return format_; }
  float float_scale() const { return float_scale_; }

 private:
  SampleFormat format_;
  bool inverted_;
  bool calibrated_ = false;
  float float_scale_ = 1.0f;
  mutable std::vector<std::int16_t> levels_;  ///< packed formats: scratch for the unpacked values
};

}  // namespace deepnav
