#pragma once
// The INS-steered side of one channel (ultra-tight tracking): a ChannelController that,
// while the navigation filter holds the channel, turns each integration into a
// discriminator sample for the filter (its outbox) and applies the NCO commands the filter
// publishes between blocks (its inbox). It never reaches into the channel or the
// receiver: it reads the ChannelView it is given and answers with ChannelDecisions, so
// channels it steers can track on worker threads.
//
// One controller per PRN for the receiver's life: what it remembers of the carrier phase
// and the last prompt carries over when the PRN's channel is dropped and acquired again.
#include <complex>
#include <cstdint>
#include <optional>
#include <vector>

#include "aiding/broadcast_ephemeris.hpp"
#include "aiding/data_wipeoff.hpp"
#include "aiding/integration_cn0_estimator.hpp"
#include "aiding/long_integrator.hpp"
#include "aiding/phase_rate_window.hpp"
#include "receiver/tracking/channel_controller.hpp"
#include "signals/ephemeris.hpp"

namespace deepnav::aiding {

/// Which channels the filter takes over.
enum class Engagement {
  none,        ///< scalar loops everywhere
  faded_only,  ///< only channels whose signal has faded (INS coasting through outages)
  all,         ///< ultra-tight: every channel that can be steered
};

struct UltraTightConfig {
  /// The aided lock criterion: an integration is a measurement when its code discriminator's
  /// predicted noise (code_sigma_chips at its C/N0, length and coherent pieces) is no larger
  /// than that of a 10 ms integration at this C/N0. Weaker ones still steer (the phase loop)
  /// but are not measurements. For 10 ms integrations this is the C/N0 itself; a 200 ms
  /// data-wiped integration passes down to about 5 dB-Hz (where the C/N0 estimate, not the
  /// discriminator, becomes the limit), ten 20 ms bits summed in power down to about 9.
  double min_cn0_dbhz = 18.0;
  double max_code_correction_chips = 5.0;  ///< a larger jump means the channel is not where the filter thinks
  bool carrier_phase_tracking = true;
  double carrier_phase_gain = 0.25;    ///< fraction of the Costas error removed per integration
  double faded_below_dbhz = 26.0;      ///< faded_only: take a channel over below this C/N0
  double recovered_above_dbhz = 32.0;  ///< faded_only: give it back above this
  /// Long integration of weak steered channels (data wipe-off); coherent_ms = 20 turns the
  /// wipe-off off (bit-edge-limited integrations, summed in power up to noncoherent_ms).
  LongIntegrationConfig long_integration;
  double long_phase_gain = 0.5;  ///< fraction of a long integration's phase error removed
  /// Galileo E1 channels: pilot integrations of coherent_ms, of weak_coherent_ms (up to 100
  /// ms, the secondary code's period) below long_integration.enter_below_dbhz until above
  /// leave_above_dbhz. No data on the pilot: nothing to wipe off, nothing to predict.
  int e1_coherent_ms = 20;
  int e1_weak_coherent_ms = 100;
};

/// One channel's discriminator outputs from one integration.
struct DiscriminatorSample {
  int prn = 0;  ///< PRN or SVID of the satellite its ephemeris names the system of
  std::int64_t mid_sample = 0;
  double replica_transmit_sow = 0.0;  ///< replica transmit time at mid_sample
  double code_error_chips = 0.0;      ///< signal minus replica (positive: replica lags)
  double spacing_chips = 0.0;         ///< early-late spacing it was measured with (the epoch's)
  /// Phase-locked: the mean carrier frequency over the window that just closed (adjoining
  /// windows of about 100 ms); otherwise NCO Doppler plus the frequency discriminator, when
  /// the previous integration adjoins.
  std::optional<double> doppler_hz;  ///< none from a non-coherent integration (no carrier phase)
  std::int64_t doppler_sample = 0;  ///< where that Doppler refers to (mid-window, or the two integrations' common edge)
  double rate_window_s = 0.0;       ///< > 0: doppler_hz is a phase-based mean over this window
  int frequency_pairs = 1;          ///< frequency discriminator pairs averaged into doppler_hz
  double cn0_dbhz = 0.0;
  double integration_s = 0.0;
  double piece_s = 0.0;      ///< > 0: pieces of this coherent length summed in power
  bool data_wiped = false;   ///< coherent across data bits, their signs removed
  bool measurement = false;  ///< passes the aided lock criterion (UltraTightConfig::min_cn0_dbhz)
  /// The code error's sigma is at least this (chips): what the channel's latest
  /// discriminators scatter by (E1 channels; 0: the C/N0 model alone).
  double code_sigma_floor_chips = 0.0;
  BroadcastEphemeris ephemeris;
  SatelliteId satellite() const { return {system_of(ephemeris), prn}; }
};

/// Whether the filter can take a channel over: bit edges known, not lost, subframe timing,
/// an ephemeris and the receiver clock.
bool can_steer(bool bit_synced, ChannelState state, bool decoder_synchronised, bool has_ephemeris);

class SteeredChannelController final : public ChannelController {
 public:
  /// `engagement` is the filter's current choice, written only between blocks.
  SteeredChannelController(const UltraTightConfig& config, double sample_rate_hz, const Engagement& engagement);

  ChannelDecision on_epoch(const CorrelatorEpoch& epoch, const ChannelView& view) override;
  ChannelDecision between_blocks(const ChannelView& view) override;
  /// The channel is gone: not steered any more, nothing queued or published for it.
  void channel_ended() override {
    release();
    inbox_release_ = false;
  }

  // The filter's side, between blocks only.
  bool steered() const { return steered_; }
  /// The discriminator samples since the last call, in time order.
  std::vector<DiscriminatorSample> take_samples();
  /// The command for the next block; the controller adds its pending carrier-phase correction.
  void publish(const NcoCommand& command);
  /// Give the channel back to its own loops (its loss detection on again).
  void publish_release();
  /// Drops queued samples and any published command; gives the channel back.
  void release();
  /// Whether the channel is integrating long (weak signal) and how its data wipe-off stands.
  bool long_integration() const { return long_mode_; }
  const DataWipeoff& wipeoff() const { return wipeoff_; }

 private:
  /// The channel's own integration (10 ms): the discriminators as they always were.
  void short_sample(const CorrelatorEpoch& e, const ChannelView& view, const std::optional<double>& doppler);
  /// A long integration (weak signal): discriminators on the summed or wiped bits.
  void long_sample(const SteeredIntegration& s, const ChannelView& view);
  /// Queues a finished sample for the filter (its ephemeris attached; a measurement marks
  /// the channel locked until `end_sample` plus the hold time).
  void queue(DiscriminatorSample d, std::int64_t end_sample, const ChannelView& view);
  /// Enters or leaves long integration on the C/N0 of the integrations so far.
  void choose_integration(const CorrelatorEpoch& e);
  void leave_long_integration();
  /// Locked: an integration passed the aided lock criterion within the last second.
  SignalLockReport lock_report(std::int64_t end_sample, double cn0_dbhz) const;
  /// Phase-window (delta range) Doppler into `d` when the integration closes a window.
  void phase_window_rate(DiscriminatorSample& d, std::int64_t end, double phase_cycles, int samples);

  const UltraTightConfig& cfg_;
  double fs_;
  const Engagement& engagement_;
  bool steered_ = false;
  // Memory of the channel's integrations.
  std::complex<double> prompt_;
  std::int64_t end_sample_ = 0;
  double doppler_hz_ = 0.0;
  double phase_correction_cycles_ = 0.0;    ///< pending Costas correction for the next command
  double applied_correction_cycles_ = 0.0;  ///< correction applied since the last integration ended
  PhaseRateWindow rate_window_;             ///< carrier phase: NCO plus Costas error
  // Long integration.
  bool long_mode_ = false;
  DataWipeoff wipeoff_;
  LongIntegrator long_;
  IntegrationCn0Estimator cn0_;
  std::optional<SteeredIntegration> last_long_;       ///< the previous data-wiped integration
  std::optional<std::int64_t> last_measurement_end_;  ///< end of the latest integration that was a measurement
  std::vector<DiscriminatorSample> outbox_;
  std::optional<NcoCommand> inbox_command_;
  bool inbox_release_ = false;
};

}  // namespace deepnav::aiding
