#pragma once
// Filter-guided search for one satellite: a narrow code/Doppler window around where an
// outside navigation filter predicts the signal (SignalPrediction), searched with long
// integrations, block by block as the samples arrive.
//
// Why not the FFT acquisition: it searches all 1023 chips and +-5 kHz with 1 ms blocks (10
// summed), which needs about 35 dB-Hz. A filter that knows the position, the clock and the
// satellite's orbit knows the code phase to metres and the Doppler to a hertz, so a handful
// of cells remain, and each can be integrated for seconds: the prediction also gives the
// data-bit edges (the transmit time), so coherent pieces are whole 20 ms bits, summed in
// power. Found down to about 15 dB-Hz within 4 s (see the tests).
//
// Cells: each correlate() call gives five taps 0.25 chip apart (very-early, early, prompt,
// late, very-late at +0.5, +0.25, 0, -0.25, -0.5 chip); calls 1.25 chips apart tile the
// code window. Doppler bins are 20 Hz apart (the worst offset, 10 Hz, costs 0.6 dB over a
// 20 ms piece). Each call's noise tap (prompt timing on another PRN's code) gives the noise
// power, averaged over all calls and pieces.
// Test: cell power summed over K pieces and divided by the noise power is Gamma(K, 1) under
// noise alone; the threshold holds a false-alarm probability over all cells, shared between
// the checks made (one per check interval, up to the longest dwell).
#include <complex>
#include <cstdint>
#include <optional>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "signals/ca_code.hpp"

namespace deepnav {

/// Where an outside filter predicts the signal of a satellite the receiver does not track.
struct SignalPrediction {
  int prn = 0;
  std::int64_t sample = 0;         ///< absolute sample index the prediction refers to
  double transmit_sow = 0.0;       ///< transmit time (GPS seconds of week) of the signal arriving there
  double doppler_hz = 0.0;         ///< carrier Doppler there, the receiver clock's drift included
  double doppler_rate_hzps = 0.0;  ///< its rate of change
  double code_sigma_chips = 0.0;   ///< 1-sigma of the predicted code phase
  double doppler_sigma_hz = 0.0;   ///< 1-sigma of the predicted Doppler
  double elevation_deg = 0.0;      ///< for messages
};

struct GuidedSearchConfig {
  double sigmas = 4.0;                     ///< half-widths of the window: this many predicted sigmas ...
  double min_code_half_width_chips = 1.0;  ///< ... and at least these
  double min_doppler_half_width_hz = 20.0;
  double max_code_half_width_chips = 8.0;  ///< a wider prediction is not narrow: no guided search
  double max_doppler_half_width_hz = 200.0;
  double doppler_step_hz = 20.0;
  double check_every_s = 1.0;  ///< test the cells this often ...
  double max_dwell_s = 4.0;    ///< ... up to this long, then give up
  double pfa = 1e-4;           ///< false-alarm probability of a whole search (all cells, all checks)
};

/// A signal found: where, against the prediction.
struct GuidedDetection {
  int prn = 0;
  double code_offset_chips = 0.0;  ///< signal minus prediction (positive: the signal is ahead)
  double doppler_offset_hz = 0.0;
  double cn0_dbhz = 0.0;   ///< from the cell's power against the noise
  double statistic = 0.0;  ///< the cell's normalised power sum
  double threshold = 0.0;
  double dwell_s = 0.0;  ///< signal integrated before the detection
};

/// Where to start tracking a signal found by a guided search, at a given sample.
struct GuidedStart {
  ChannelStart channel;               ///< code phase, Doppler and the data-bit edge (from the transmit time)
  double period0_transmit_sow = 0.0;  ///< transmit time at the start of the channel's code period 0 (whole ms)
};

/// Whether a detection at `found_doppler_hz` and `found_cn0_dbhz` may be the
/// cross-correlation of a tracked satellite: C/A codes cross-correlate (about -21 to -24 dB)
/// where their Doppler difference lies near a multiple of the code's 1 kHz lines; within
/// `window_hz` of one, a detection more than `margin_db` below the tracked signal cannot be
/// told from it.
bool cross_correlation_suspect(double found_doppler_hz, double found_cn0_dbhz, double tracked_doppler_hz,
                               double tracked_cn0_dbhz, double window_hz, double margin_db);

class GuidedSearch {
 public:
  /// Throws std::invalid_argument when the prediction's window is not narrow
  /// (is_narrow() is the check without the exception).
  GuidedSearch(const GuidedSearchConfig& config, const SignalPrediction& prediction, double sample_rate_hz,
               double if_hz);
  static bool is_narrow(const GuidedSearchConfig& config, const SignalPrediction& prediction);

  enum class Outcome { searching, found, not_found };
  /// The next block of samples (in order; samples before the prediction's sample are
  /// skipped). A gap in the indices drops the piece in progress.
  void add(const SampleBlock& block);
  Outcome outcome() const { return outcome_; }
  const SignalPrediction& prediction() const { return prediction_; }
  /// Once found.
  const std::optional<GuidedDetection>& detection() const { return detection_; }
  /// Once found: the channel start at `sample` (at or after the last sample added).
  GuidedStart start_at(std::int64_t sample, int channel) const;
  int cells() const { return static_cast<int>(power_.size()); }
  /// Seconds of signal integrated so far (whole pieces).
  double dwell_s() const;

 private:
  /// Code phase (chips, unwrapped: 0 is the start of the code period the prediction's
  /// sample lies in) at `sample` of a replica `offset_chips` and `doppler_offset_hz` from the prediction.
  double code_chips_at(double offset_chips, double doppler_offset_hz, std::int64_t sample) const;
  double doppler_at(double doppler_offset_hz, std::int64_t sample) const;
  void correlate_span(const SampleBlock& block, std::int64_t first, int n);
  void finish_piece();
  void check();
  /// First sample of data bit m after the prediction's sample (m = 0: the first edge at or after it).
  std::int64_t bit_edge_sample(std::int64_t m) const;
  /// The first bit whose edge is at or after `sample`.
  std::int64_t first_bit_from(std::int64_t sample) const;
  /// Code offset (chips) of code cell c of a bin: calls are 1.25 chips apart, taps 0.25.
  double cell_offset_chips(int c) const;

  GuidedSearchConfig cfg_;
  SignalPrediction prediction_;
  double fs_, if_hz_;
  const CaCodeChips* code_;
  const CaCodeChips* noise_code_;
  int calls_ = 0;                           ///< correlate() calls per bin (code window / 1.25 chips)
  std::vector<double> doppler_offsets_hz_;  ///< of each bin
  static constexpr int kTaps = 5;
  static constexpr double kTapSpacing_chips = 0.25;
  // Cells: [bin][call][tap], flattened.
  std::vector<std::complex<double>> piece_;  ///< sums of the piece in progress
  std::vector<double> power_;                ///< summed |piece|^2
  double noise_power_sum_ = 0.0;
  long noise_terms_ = 0;
  std::vector<std::complex<double>> piece_noise_;  ///< noise taps of the piece in progress, [bin][call]
  std::int64_t bit_ = 0;          ///< the bit (piece) in progress, counted from the prediction's sample
  std::int64_t piece_first_ = 0;  ///< its first sample
  std::int64_t piece_end_ = 0;    ///< one past its last sample
  bool piece_started_ = false;    ///< samples of it were correlated
  double bit_phase_s_ = 0.0;      ///< transmit time of the prediction past its last bit edge
  std::int64_t next_sample_;
  int pieces_ = 0;
  int checks_made_ = 0;
  int checks_total_ = 0;
  int pieces_per_check_ = 0;
  Outcome outcome_ = Outcome::searching;
  std::optional<GuidedDetection> detection_;
};

}  // namespace deepnav
