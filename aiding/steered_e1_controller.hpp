#pragma once
// The INS-steered side of one Galileo E1 channel (ultra-tight tracking): the E1 counterpart
// of SteeredChannelController. While the navigation filter holds the channel, each pilot
// integration becomes a discriminator sample for the filter (its outbox), and the NCO
// commands the filter publishes between blocks are applied (its inbox).
//
// What the pilot changes. Once the channel has wiped the CS25 secondary code, E1-C carries
// no data: every integration is coherent whatever its length, its four-quadrant phase error
// has no half-cycle ambiguity, and nothing has to be predicted or wiped off. Where a GPS
// channel needs the LNAV bits to integrate beyond 20 ms, a steered E1 channel needs only
// the filter's Doppler to hold over the integration: below the weak-signal C/N0 it integrates
// 100 ms (the secondary code's period) instead of 20 ms, five times the post-integration SNR
// for the code and phase discriminators.
//
// Discriminators: the BOC(1,1) early-late envelope on the pilot (code), the pilot's
// four-quadrant phase (a first-order phase loop on top of the filter's Doppler, and the
// rate as the mean frequency over adjoining ~100 ms windows of carrier phase while phase
// locked; no rate otherwise: the frequency discriminator of weak pilot integrations is
// worth less than the GPS channels' beside it). C/N0 from the pilot integrations
// (IntegrationCn0Estimator, the noise tap as reference), reported for the whole E1 signal as
// the channel does.
//
// A sudden change (a jammer switched on) reaches that C/N0 only after seconds: its window is
// 2 s and its noise reference ten times longer, so the estimate still reads the signal as it
// was while the discriminators are already noise. The last ten integrations say it at once:
// their code errors' RMS is a floor under the pseudorange's sigma (no measurement before
// there are ten), and their prompts' mean I over mean |Q| must show phase lock before a
// rate is taken.
//
// Only ultra-tight engages it (Engagement::all): in loose and tight mode the E1 channels keep
// their own loops through fades. One controller per SVID for the receiver's life, as for GPS.
#include <complex>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "aiding/integration_cn0_estimator.hpp"
#include "aiding/phase_rate_window.hpp"
#include "aiding/steered_channel_controller.hpp"
#include "receiver/tracking/e1_channel_controller.hpp"

namespace deepnav::aiding {

/// Whether the filter can take an E1 channel over: tracking on the wiped pilot, its code
/// periods dated by the I/NAV pages, an ephemeris, the receiver clock, and the Galileo system
/// offset known (the filter's one clock is GPS time).
bool can_steer_e1(E1ChannelState state, bool time_mark, bool has_ephemeris, bool clock_set, bool offset_known);

class SteeredE1Controller final : public E1ChannelController {
 public:
  /// `engagement` and `offset_known` are the filter's, written only between blocks.
  SteeredE1Controller(const UltraTightConfig& config, double sample_rate_hz, const Engagement& engagement,
                      const bool& offset_known);

  E1ChannelDecision on_epoch(const E1CorrelatorEpoch& epoch, const E1ChannelView& view) override;
  E1ChannelDecision between_blocks(const E1ChannelView& view) override;
  void channel_ended() override {
    release();
    inbox_release_ = false;
  }

  // The filter's side, between blocks only.
  bool steered() const { return steered_; }
  std::vector<DiscriminatorSample> take_samples();
  /// The command for the next block; the controller adds its pending phase correction.
  void publish(const NcoCommand& command);
  /// Give the channel back to its own loops.
  void publish_release();
  /// Drops queued samples and any published command; gives the channel back.
  void release();
  /// Whether it integrates the weak-signal length now.
  bool long_integration() const { return long_mode_; }

 private:
  /// Gives the channel back (its own loops and loss rule again); what the decision says.
  E1ChannelDecision let_go(const E1ChannelView& view);
  /// The channel's own pilot integration length (code periods), to return it to.
  static int own_coherent_periods(const E1ChannelView& view);
  /// What the integrations so far said (length chosen, phase window, recent scatter) no
  /// longer holds: the channel is given back.
  void forget_signal();
  /// The integration length for the C/N0 so far: the periods to ask for when it changes.
  std::optional<int> choose_length(const E1CorrelatorEpoch& e);
  DiscriminatorSample sample_of(const E1CorrelatorEpoch& e, double transmit_sow, double cn0_dbhz) const;
  void rate_of(DiscriminatorSample& d, const E1CorrelatorEpoch& e, double phase_error_cycles);
  /// The recent integrations: RMS of their code errors and whether they show phase lock
  /// (none until there are enough of them).
  std::optional<double> recent_code_rms_chips() const;
  bool recently_phase_locked() const;
  SignalLockReport lock_report(std::int64_t end_sample, double cn0_dbhz) const;

  const UltraTightConfig& cfg_;
  double fs_;
  const Engagement& engagement_;
  const bool& offset_known_;
  bool steered_ = false;
  bool long_mode_ = false;
  IntegrationCn0Estimator cn0_;
  PhaseRateWindow rate_window_;
  struct Recent {
    std::complex<double> prompt;
    double code_error_chips = 0.0;
  };
  std::deque<Recent> recent_;             ///< the latest integrations, newest last
  double phase_correction_cycles_ = 0.0;  ///< pending phase-loop correction for the next command
  std::optional<std::int64_t> last_measurement_end_;
  std::vector<DiscriminatorSample> outbox_;
  std::optional<NcoCommand> inbox_command_;
  bool inbox_release_ = false;
};

}  // namespace deepnav::aiding
