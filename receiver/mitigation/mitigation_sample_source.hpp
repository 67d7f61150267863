#pragma once
// A SampleSource decorator that runs interference mitigation between any source and
// the receiver: it reads the wrapped source, filters the samples (pulse blanking,
// adaptive notch, frequency excision or blanking followed by excision) and delivers
// them with their original absolute indices, so the receiver needs no change.
//
// Level: blanking alone passes samples bit-exact. After the floating-point filters an
// output level control holds the RMS at 2048 (power over 64-sample windows, 10 ms time
// constant, started from the first 4096 filtered samples). When a jammer appears the
// converter's AGC turns its gain down, so after the jammer is removed the satellites and
// noise are much weaker in converter units; the level control gives the receiver the
// same level as before, within about 10 ms, instead of a step that its slowly averaged
// C/N0 noise reference would read as a signal loss, and keeps the residual many int16
// steps wide instead of rounding it away.
// Gaps: a jump in the wrapped source's indices flushes the filters' pending samples,
// restarts them after the gap and reports the gap before the samples that follow it.
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "receiver/mitigation/mitigation_config.hpp"
#include "receiver/mitigation/mitigation_stage.hpp"
#include "receiver/sources/sample_source.hpp"

namespace deepnav {

class MitigationSampleSource final : public SampleSource {
 public:
  /// Validates the configuration against the source's sample rate (std::invalid_argument
  /// naming the field). `inner` must outlive this object. With mode none, read() passes
  /// the wrapped source's samples through untouched.
  MitigationSampleSource(SampleSource& inner, const MitigationConfig& config);
  ~MitigationSampleSource() override;

  double sample_rate_hz() const override { return inner_.sample_rate_hz(); }
  double intermediate_frequency_hz() const override { return inner_.intermediate_frequency_hz(); }
  bool is_real() const override { return inner_.is_real(); }
  std::size_t read(std::span<Sample> out) override;
  std::int64_t next_sample_index() const override { return next_index_; }
  bool at_end() const override { return at_end_; }
  bool gap_sizes_exact() const override { return inner_.gap_sizes_exact(); }

  MitigationMode mode() const { return config_.mode; }
  /// Gain the level control applies now (1 for none and blanking).
  float output_gain() const { return gain_; }
  /// The stages in processing order (for statistics and tests).
  const std::vector<std::unique_ptr<MitigationStage>>& stages() const { return stages_; }

 private:
  struct Segment {
    std::int64_t first_index = 0;
    std::vector<Sample> samples;
    std::size_t delivered = 0;
  };
  std::size_t read_through(std::span<Sample> out);
  /// Reads one piece of the wrapped source and appends its filtered samples to the queue.
  void pull();
  /// The next piece of the wrapped source (a held one first) and its first index; false at the end.
  bool take_piece(std::vector<Sample>& dest, std::int64_t& first);
  /// Runs the stages over `count` samples of work_ and queues the results (minus the
  /// samples still to drop after a restart) as a new segment.
  void filter_into_queue(std::size_t count);
  /// Pushes the samples still inside the filters out by feeding zeros.
  void flush();
  /// Starts the level control from the power of the first filtered samples.
  void set_level(std::span<const std::complex<float>> first);
  /// Scales filtered samples in place by the level control's gain and updates it.
  void hold_level(std::span<std::complex<float>> w);
  std::size_t total_delay() const;

  SampleSource& inner_;
  MitigationConfig config_;
  std::vector<std::unique_ptr<MitigationStage>> stages_;
  std::deque<Segment> queue_;
  std::vector<Sample> raw_, piece_;
  std::vector<Sample> held_;  ///< a piece read past a gap while gathering samples for the gain
  std::int64_t held_first_ = 0;
  bool has_held_ = false, inner_eof_ = false;
  std::vector<std::complex<float>> work_;
  std::int64_t next_index_ = 0;         ///< one past the last sample delivered
  std::int64_t next_input_index_ = -1;  ///< the wrapped source's next contiguous index; -1 before the first
  std::int64_t next_output_index_ = 0;  ///< index of the next sample the filters hand out
  std::size_t to_drop_ = 0;             ///< filter outputs that precede the current stream start
  float gain_ = 1.0f;
  bool normalize_ = false;
  double level_power_ = 0.0, window_power_ = 0.0;  ///< filtered output power (before the gain)
  int window_count_ = 0;
  bool level_set_ = false, inner_done_ = false, at_end_ = false;
};

}  // namespace deepnav
