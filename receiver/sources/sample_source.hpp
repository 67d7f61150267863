#pragma once
// Where the receiver's samples come from. Every source (file, network stream,
// in-process synthesizer) delivers consecutive blocks of complex int16 samples,
// the receiver's internal format, each tagged with the absolute index of its
// first sample: that index is the master clock of a run.
#include <complex>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace deepnav {

/// One complex baseband-or-IF sample. Real-input sources deliver Q = 0.
using Sample = std::complex<std::int16_t>;

/// A block of consecutive samples and the absolute index of the first one.
struct SampleBlock {
  std::int64_t first_sample_index = 0;
  std::vector<Sample> samples;
  /// What the correlator would otherwise work out per channel, computed once for the block
  /// (prepare_for_correlation()); whoever changes `samples` clears them.
  int magnitude_bits = -1;           ///< bits of the largest |I| or |Q| in `samples`; -1: unknown
  std::vector<std::int16_t> planar;  ///< I of every sample, then Q; empty: not prepared
};

/// Samples that never arrived (a dropped network packet, an overrun): the
/// absolute index of the first missing sample and how many are missing.
struct SampleGap {
  std::int64_t first_missing_index = 0;
  std::int64_t missing_count = 0;
};

class SampleSource {
 public:
  using GapHandler = std::function<void(const SampleGap&)>;

  virtual ~SampleSource() = default;

  virtual double sample_rate_hz() const = 0;
  /// Centre of the signal in the delivered samples (0 for baseband I/Q).
  virtual double intermediate_frequency_hz() const = 0;
  /// True when the samples are real (Q always 0): the signal then has an
  /// image at -IF that the receiver must keep away from.
  virtual bool is_real() const = 0;

  /// Blocking read of up to out.size() samples into out; returns how many were
  /// written. Returns 0 only at the end of the stream; a short read is not an
  /// end. The samples of one call are contiguous (never span a gap), so the
  /// first of them has index next_sample_index() - count after the call.
  virtual std::size_t read(std::span<Sample> out) = 0;
  /// Absolute index one past the last sample delivered. A source that loses
  /// samples advances it past the gap and reports the gap (report_gap).
  virtual std::int64_t next_sample_index() const = 0;
  /// True once read() has returned 0 (nothing more will ever come).
  virtual bool at_end() const = 0;
  /// False for a source whose gap sizes are estimates (rtl_tcp: told from arrival times, to
  /// some microseconds): the receiver then re-acquires every satellite after a gap instead
  /// of carrying its channels across it (a code phase a few samples off is no phase at all).
  virtual bool gap_sizes_exact() const { return true; }

  /// One read() of up to max_samples into block (its buffer is reused), with the
  /// index of its first sample; false at the end. The block may be short.
  bool read_block(SampleBlock& block, std::size_t max_samples);
  /// Called for every gap a source detects; without a handler gaps are counted only.
  void set_gap_handler(GapHandler handler) { gap_handler_ = std::move(handler); }
  std::int64_t lost_sample_count() const { return lost_samples_; }

 protected:
  /// Sources call this when samples went missing, before delivering the ones after the gap.
  void report_gap(const SampleGap& gap);

 private:
  GapHandler gap_handler_;
  std::int64_t lost_samples_ = 0;
};

}  // namespace deepnav
