#pragma once
// One Galileo E1 OS tracking channel: code and carrier NCOs, the E1 correlator bank (BOC(1,1)
// replicas: very early/early/prompt/late/very late on the E1-C pilot, prompt on the E1-B data,
// a noise reference), 4 ms integrations per primary code period, synchronisation to the CS25
// secondary code, then secondary-wiped pilot integrations of several code periods, lock
// monitoring, a guard against false lock on a BOC side peak, and the E1-B symbols (one per
// code period).
//
// States: pull_in (FLL-assisted Costas loop, pull_in_s), secondary_sync (Costas loop while the
// CS25 phase is searched), tracking (secondary code wiped: the pilot has no sign ambiguity and
// a pure PLL runs, on 4 ms integrations until the phase lock flag is up, then on
// coherent_ms_after_sync integrations), lost. At synchronisation the channel
// turns its carrier phase by half a cycle where the Costas loop sat on the negative side, so
// from then on the wiped pilot prompt is positive real, and the E1-B symbols' sign is absolute:
// the ICD's composite signal sends E1-C in antiphase with E1-B, so a data symbol of logic 0
// appears as a negative data prompt (the channel reports it as a positive soft symbol).
//
// As the GPS channel, it is steered only by NcoCommands (apply()), from its E1LoopController
// or an outside filter; the one exception is the side-peak guard's half-chip jump (with its
// half-cycle carrier turn), which the channel applies itself when the very-early or very-late
// tap keeps beating the prompt, and after more jumps than allowed declares the channel lost.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "receiver/tracking/e1_correlator.hpp"
#include "receiver/tracking/e1_secondary_sync.hpp"
#include "receiver/tracking/e1_side_peak_guard.hpp"
#include "receiver/tracking/e1_tracking_types.hpp"
#include "receiver/tracking/lock_detectors.hpp"
#include "receiver/tracking/tracking_types.hpp"
#include "signals/satellite_id.hpp"

namespace deepnav {

struct E1TrackingConfig {
  /// At least 2.1 Msps: a sample per BOC(1,1) half chip, with Doppler to spare (4 Msps or more
  /// resolves the correlation peak's shape).
  double sample_rate_hz = 4.092e6;
  double if_hz = 0.0;
  /// Early-late spacing: narrow, well inside the BOC(1,1) main peak's linear part (+-1/3 chip).
  double spacing_chips = 0.2;
  /// Very-early/very-late spacing: 1 chip puts them on the +-0.5 chip side peaks.
  double very_spacing_chips = 1.0;
  /// Pilot integration once the secondary code is wiped: a multiple of 4 up to 100.
  int coherent_ms_after_sync = 20;
  double pull_in_s = 0.3;  ///< FLL-assisted pull-in before the secondary code search
  int secondary_window_periods = 50;
  /// No CS25 phase this long after pull-in (a Costas loop held on a false frequency, or no
  /// E1-C there): loss of lock, for the owner to search again.
  double secondary_timeout_s = 2.0;
  int side_peak_threshold = 20;  ///< net integrations for a bump jump
  int side_peak_max_jumps = 2;   ///< jumps allowed; one more declares loss
  double lost_cn0_dbhz = 25.0;   ///< below this (E1 total) for lost_after_s: loss of lock
  double lost_after_s = 1.0;
  LockThresholds lock{1.5, 1.25, 29.0, 26.0, 5, 0.2};  ///< C/N0 thresholds on the E1 total
};

/// Where tracking starts: an acquisition result.
struct E1ChannelStart {
  SatelliteId satellite{GnssSystem::galileo, 1};
  double doppler_hz = 0.0;
  double code_phase_chips = 0.0;  ///< prompt code phase at sample `sample_index`, [0, 4092)
  std::int64_t sample_index = 0;
  int channel = 0;  ///< the owner's channel number, copied into every epoch
};

/// The E1 pilot's power fraction seen by a BOC(1,1) replica: half the signal, alpha^2 of it.
double e1_pilot_power_fraction();

class E1TrackingChannel {
 public:
  /// Throws std::invalid_argument for a non-Galileo satellite, a PRN without codes, or bad
  /// settings (naming the setting).
  E1TrackingChannel(const E1TrackingConfig& config, const E1ChannelStart& start);

  /// Consumes a block (any size); each completed integration goes to `on_epoch` at once, so a
  /// command it apply()s acts from the very next sample. Samples before the channel's next
  /// sample are skipped; a gap drops the integration in progress and carries the NCOs across.
  void process(const SampleBlock& block, const std::function<void(const E1CorrelatorEpoch&)>& on_epoch);
  /// New NCO rates (and optional one-off phase corrections) from the next sample on.
  void apply(const NcoCommand& command);
  /// The weak-signal loss rule (lost_cn0_dbhz for lost_after_s) on or off: off while an
  /// outside filter steers the channel through a fade. The side-peak guard stays on.
  void set_loss_detection(bool on);
  /// Once tracking (secondary code wiped): pilot integrations of `periods` code periods
  /// (1 to 25, 4 to 100 ms) from the one under way on (it ends when it holds that many).
  /// Ignored before; throws std::invalid_argument outside 1..25.
  void set_coherent_periods(int periods);
  int coherent_periods() const { return coherent_periods_; }

  const SatelliteId& satellite() const { return start_.satellite; }
  const E1TrackingConfig& config() const { return cfg_; }
  E1ChannelState state() const { return state_; }
  double cn0_dbhz() const;
  bool phase_locked() const { return lock_.pll_locked(); }
  bool code_locked() const { return lock_.code_locked(); }
  const std::optional<SecondaryCodePhase>& secondary_phase() const { return secondary_; }
  int side_peak_jumps() const { return guard_.jumps(); }
  /// Code phase (chips, unwrapped from the start: periods * 4092 + phase) at an absolute sample
  /// index inside or just after the last block processed.
  double code_chips_at(std::int64_t sample_index) const;
  double carrier_phase_cycles() const { return carrier_phase_cycles_; }
  std::int64_t next_sample() const { return next_sample_; }

 private:
  /// Ends a code period; the epoch when an integration ends with it.
  std::optional<E1CorrelatorEpoch> finish_code_period();
  void monitor(E1CorrelatorEpoch& epoch);
  void jump_replica(double chips);
  void reset_integration();

  E1TrackingConfig cfg_;
  E1ChannelStart start_;
  E1CorrelatorCodes codes_;
  E1ChannelState state_ = E1ChannelState::pull_in;
  // NCO state at next_sample_.
  std::int64_t next_sample_;
  double code_phase_chips_;
  std::int64_t code_period_ = 0;
  double carrier_phase_cycles_ = 0.0;  ///< Doppler part only; the IF part follows the sample index
  NcoCommand nco_;
  // Code period in progress.
  E1CorrelatorSums period_;
  std::int64_t period_first_ = -1;
  int period_samples_ = 0;
  // Integration in progress (secondary-wiped once synchronised).
  E1CorrelatorSums acc_;
  std::int64_t acc_first_ = -1;
  int acc_samples_ = 0;
  int acc_noise_samples_ = 0;  ///< samples of the integration's first period, the one with the noise tap
  int acc_periods_ = 0;
  int coherent_periods_ = 1;
  std::vector<E1bSymbol> symbols_;
  // Monitoring.
  LockDetector lock_;
  SecondaryCodeSynchronizer sync_;
  std::optional<SecondaryCodePhase> secondary_;
  SidePeakGuard guard_;
  double tracked_s_ = 0.0;
  double low_since_s_ = -1.0;
  bool loss_detection_ = true;
};

}  // namespace deepnav
