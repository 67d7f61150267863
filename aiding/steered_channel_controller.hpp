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

#include "receiver/channel_controller.hpp"
#include "signals/ephemeris.hpp"

namespace deepnav::aiding {

/// Which channels the filter takes over.
enum class Engagement {
  none,        ///< scalar loops everywhere
  faded_only,  ///< only channels whose signal has faded (INS coasting through outages)
  all,         ///< ultra-tight: every channel that can be steered
};

struct UltraTightConfig {
  double min_cn0_dbhz = 18.0;               ///< weaker integrations steer but are not measurements
  double max_code_correction_chips = 5.0;   ///< a larger jump means the channel is not where the filter thinks
  bool carrier_phase_tracking = true;
  double carrier_phase_gain = 0.25;         ///< fraction of the Costas error removed per integration
  double faded_below_dbhz = 26.0;           ///< faded_only: take a channel over below this C/N0
  double recovered_above_dbhz = 32.0;       ///< faded_only: give it back above this
};

/// One channel's discriminator outputs from one integration.
struct DiscriminatorSample {
  int prn = 0;
  std::int64_t mid_sample = 0;
  double replica_transmit_sow = 0.0;   ///< replica transmit time at mid_sample
  double code_error_chips = 0.0;       ///< signal minus replica (positive: replica lags)
  double spacing_chips = 0.0;          ///< early-late spacing it was measured with (the epoch's)
  /// Phase-locked: the mean carrier frequency over the window that just closed (adjoining
  /// windows of about 100 ms); otherwise NCO Doppler plus the frequency discriminator, when
  /// the previous integration adjoins.
  std::optional<double> doppler_hz;
  std::int64_t doppler_sample = 0;     ///< where that Doppler refers to (mid-window, or the two integrations' common edge)
  double rate_window_s = 0.0;          ///< > 0: doppler_hz is a phase-based mean over this window
  double cn0_dbhz = 0.0;
  double integration_s = 0.0;
  Ephemeris ephemeris;
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

 private:
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
  std::optional<std::int64_t> rate_window_start_;  ///< integration end where the current phase window began
  double rate_window_start_cycles_ = 0.0;          ///< carrier phase there (NCO plus Costas error)
  std::vector<DiscriminatorSample> outbox_;
  std::optional<NcoCommand> inbox_command_;
  bool inbox_release_ = false;
};

}  // namespace deepnav::aiding
