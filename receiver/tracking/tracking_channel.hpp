#pragma once
// One tracking channel: code and carrier NCOs, the correlator bank, integration over
// code periods (1 ms, extended up to 20 ms along data-bit edges once the bits are
// synchronised), bit synchronisation and lock monitoring. The channel is steered only
// through NcoCommands (apply()); its owner passes every epoch to the channel's
// ChannelController (channel_controller.hpp) and applies the command it answers.
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "receiver/tracking/bit_synchronizer.hpp"
#include "receiver/tracking/lock_detectors.hpp"
#include "receiver/tracking/prompt_history.hpp"
#include "receiver/tracking/tracking_types.hpp"
#include "signals/ca_code.hpp"

namespace deepnav {

struct TrackingConfig {
  double sample_rate_hz = 4.092e6;
  double if_hz = 0.0;
  double spacing_chips = 0.5;           ///< early-late spacing (the receiver's only setting of it)
  int coherent_ms_after_bit_sync = 10;  ///< 1, 2, 4, 5, 10 or 20
  double lost_cn0_dbhz = 22.0;          ///< below this for `lost_after_s`: loss of lock
  double lost_after_s = 1.0;
  double very_spacing_chips = 0.0;  ///< very-early/very-late spacing; 0: not computed
  double pull_in_s = 0.25;          ///< FLL-assisted pull-in time before bit synchronisation
  /// The noise correlator (the C/N0 reference) runs on the first code period of each
  /// integration only: one |N|^2 per integration is what the estimate averages, whatever
  /// length it was integrated over, so longer integrations need no more (after bit sync,
  /// with 10 ms integrations, it costs a tenth). true: on every code period.
  bool noise_on_every_period = false;
  LockThresholds lock;  ///< PLL and code lock flags (CorrelatorEpoch::pll_lock, code_lock)
};

/// Where tracking starts: an acquisition result.
struct ChannelStart {
  int prn = 0;
  double doppler_hz = 0.0;
  double code_phase_chips = 0.0;  ///< prompt code phase at sample `sample_index`, [0, 1023)
  std::int64_t sample_index = 0;
  int channel = 0;  ///< the owner's channel number, copied into every epoch
  /// The data-bit edge (a code period, counted from the start, at which a bit begins) when
  /// it is known beforehand (a start from a filter's prediction of the transmit time): the
  /// channel then skips pull-in and bit synchronisation and integrates along the bits at once.
  std::optional<std::int64_t> bit_edge_period;
};

enum class ChannelState { pull_in, bit_sync, tracking, lost };

class TrackingChannel {
 public:
  TrackingChannel(const TrackingConfig& config, const ChannelStart& start);

  /// Consumes a block (any size, any alignment); completed integrations are appended to `out`.
  /// Samples before the channel's next sample are skipped; a gap in the indices drops the
  /// integration in progress and carries the NCOs across it. Every completed epoch has
  /// already been through the lock monitor and the bit synchroniser (its flags are set).
  void process(const SampleBlock& block, std::vector<CorrelatorEpoch>& out);
  /// The same, handing each epoch to `on_epoch` as soon as it completes; a command the
  /// callback apply()s takes effect from the very next sample. This is the form a loop
  /// should use: with the vector form the commands of all epochs in a block only act after
  /// the block, which delays the loop by up to a block.
  void process(const SampleBlock& block, const std::function<void(const CorrelatorEpoch&)>& on_epoch);
  /// New NCO rates (and optional one-off phase corrections) from the next sample on.
  void apply(const NcoCommand& command);
  /// Whether the channel declares itself lost on weak or incoherent signal (on by default).
  /// An outside filter that keeps the replica aligned through fades turns it off.
  /// Turning it back on starts the weak-signal timer afresh.
  void set_loss_detection(bool enabled) {
    if (enabled && !loss_detection_) low_cn0_since_s_ = -1.0;
    loss_detection_ = enabled;
  }
  /// Data bits completed since the last call (empty before bit synchronisation). At bit
  /// synchronisation the bits of the prompts kept since the channel's first whole code
  /// period come first (PromptHistory), so the stream has no gap from the start.
  std::vector<PromptBit> take_bits();

  int prn() const { return start_.prn; }
  ChannelState state() const { return state_; }
  double cn0_dbhz() const { return lock_.cn0_dbhz(); }
  bool phase_locked() const { return lock_.pll_locked(); }
  bool code_locked() const { return lock_.code_locked(); }
  const LockDetector& lock_detector() const { return lock_; }
  /// Code period (ms count since the start) at which data bits begin, once synchronised.
  std::optional<std::int64_t> bit_edge_period() const { return bit_edge_; }
  double seconds_tracked() const;
  /// Code phase (chips, unwrapped from the start: periods * 1023 + phase) at an absolute
  /// sample index inside or just after the last block processed.
  double code_chips_at(std::int64_t sample_index) const;
  std::int64_t next_sample() const { return next_sample_; }
  /// Mean carrier Doppler (Hz) over about the last `window_s` seconds, from the NCO phase
  /// accumulated between integration ends: far less noisy than the loop's instantaneous
  /// frequency. nullopt until that much has been tracked.
  std::optional<double> mean_doppler_hz(double window_s) const;
  /// The sample in the middle of that window: the mean is the Doppler there (to the
  /// Doppler's second derivative), about window_s / 2 before the last integration's end.
  std::optional<double> mean_doppler_mid_sample(double window_s) const;
  /// Accumulated carrier phase (cycles, Doppler part) at the end of the last integration.
  double carrier_phase_cycles() const { return carrier_phase_cycles_; }

 private:
  /// Ends a code period; returns the epoch when an integration ends with it.
  std::optional<CorrelatorEpoch> finish_code_period();
  /// Lock monitoring and bit synchronisation of an epoch that just completed.
  void monitor(const CorrelatorEpoch& epoch);
  void bit_sync_step(const CorrelatorEpoch& epoch);
  void collect_bit(const CorrelatorEpoch& epoch);
  /// The kept prompts become bits once the edge is known; the bit in progress continues live.
  void release_history();
  void reset_integration();

  TrackingConfig cfg_;
  ChannelStart start_;
  const CaCodeChips* code_;
  const CaCodeChips* noise_code_;
  ChannelState state_ = ChannelState::pull_in;
  // NCO state at next_sample_.
  std::int64_t next_sample_;
  double code_phase_chips_;
  std::int64_t code_period_ = 0;
  double carrier_phase_cycles_ = 0.0;  ///< Doppler part only; the IF part follows the sample index
  NcoCommand nco_;
  // Integration in progress.
  std::complex<double> acc_e_, acc_p_, acc_l_, acc_ve_, acc_vl_, acc_n_;
  int acc_n_samples_ = 0;  ///< samples the noise correlator covered in this integration
  std::int64_t acc_first_ = -1;
  int acc_samples_ = 0;
  int acc_ms_ = 0;
  int coherent_ms_ = 1;
  // Monitoring.
  LockDetector lock_;
  BitSynchronizer bit_sync_;
  PromptHistory history_;  ///< 1 ms prompts before bit synchronisation
  std::optional<std::int64_t> bit_edge_;
  double low_cn0_since_s_ = -1.0;
  bool loss_detection_ = true;
  double tracked_s_ = 0.0;
  std::deque<std::pair<std::int64_t, double>> phase_history_;  ///< (sample, carrier cycles) at integration ends
  /// The latest history entry at least window_s before the last one, or nullptr.
  const std::pair<std::int64_t, double>* window_start(double window_s) const;
  // Bit assembly after bit sync.
  double bit_sum_ = 0.0;
  int bit_ms_ = 0;
  std::int64_t bit_first_sample_ = 0, bit_first_period_ = 0;
  bool bit_whole_ = true;  ///< the bit in progress began on a whole code period
  std::vector<PromptBit> bits_;
};

}  // namespace deepnav
