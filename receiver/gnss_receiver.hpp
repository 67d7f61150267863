#pragma once
// The GNSS receiver, GPS L1 C/A and Galileo E1 OS on the same samples (ReceiverConfig::systems;
// the Galileo side is a GalileoChannelSet with scalar loops, galileo_channel_set.hpp). For GPS:
// acquisition at the start and again every few seconds while a channel is free (AcquisitionSchedule); one ReceiverChannel per satellite, closed by its
// own scalar loops or, given a ChannelAiding, steered by an outside filter (ultra-tight
// aiding, see tracking/channel_controller.hpp); the navigation data in use
// (BroadcastNavigation); the receiver clock and the GPS week (ReceiverClock); observables
// at common receiver epochs, and PVT. Lost channels are released; their satellites are
// searched again by the acquisition, and with an outside filter also in a narrow window
// where the filter predicts them (GuidedReacquisition).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "receiver/acquisition/acquisition.hpp"
#include "receiver/acquisition/guided_reacquisition.hpp"
#include "receiver/acquisition/signal_diagnostics.hpp"
#include "receiver/galileo_channel_set.hpp"
#include "receiver/hot_start.hpp"
#include "receiver/pvt/pvt_solver.hpp"
#include "receiver/receiver_channel.hpp"
#include "receiver/sources/sample_source.hpp"
#include "receiver/tracking/channel_controller.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "receiver/tracking/tracking_loops.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

/// More channel threads than this is a mistake (a receiver has at most a few dozen channels).
inline constexpr unsigned kMaxReceiverThreads = 256;
/// The sample rates the receiver takes: the C/A code needs about 1 Msps, and no L1 front
/// end samples faster than 200 Msps (a 10 ms block would then be 2 million samples).
inline constexpr double kMinSampleRate_hz = 1.0e6;
inline constexpr double kMaxSampleRate_hz = 2.0e8;

struct ReceiverConfig {
  /// The systems tracked, each once: GPS L1 C/A, Galileo E1 OS (4 Msps or more), or both.
  std::vector<GnssSystem> systems{GnssSystem::gps};
  int channels = 12;                 ///< GPS channels
  unsigned threads = 1;              ///< channel worker threads (0: all cores); 1 tracks inline
  double observation_rate_hz = 1.0;  ///< up to 50
  /// GPS week near the data (0: none given). The signal broadcasts its week modulo 1024
  /// (LNAV's 10-bit WN, in subframe 1): a reference resolves it to the full week. This one,
  /// else the epoch of the assisted ephemerides, else the build date (data within about
  /// ten years of it). Given here or by assistance, the receiver clock is set as soon as four
  /// transmit times exist and checked against the first subframe 1; otherwise it waits for
  /// that subframe, so that no product carries a guessed week. A signal whose week differs
  /// from this one by more than a week is an error naming reference_week_origin.
  int reference_week = 0;
  std::string reference_week_origin = "reference week";
  double reacquire_interval_s = 5.0;
  GuidedReacquisitionConfig guided;
  AcquisitionConfig acquisition;  ///< sample rate and IF are taken from the source
  TrackingConfig tracking;
  LoopBandwidths pull_in{15.0, 10.0, 1.0};
  LoopBandwidths tracking_loops{10.0, 0.0, 0.5};
  int pll_order = 2;  ///< every channel's carrier loop, pull-in and tracking: 2, or 3 for high dynamics
  /// The Galileo channels, their acquisition and loops (when systems holds Galileo).
  GalileoReceiverSettings galileo;
  PvtConfig pvt;
  /// The atmosphere models of every range the receiver or an aided filter predicts: the
  /// PVT solution reads them from here, and so do tight coupling and the ultra-tight NCO commands
  /// (through atmosphere()).
  AtmosphereModels atmosphere;
  /// Hot start: until the receiver clock is set, each epoch is a coarse-time fix from the
  /// code phases (receiver/hot_start.hpp) with these hints; it needs ephemerides
  /// given (set_assisted_ephemerides). None: a cold or assisted start.
  std::optional<HotStartHints> hot_start;
};

/// Everything the receiver knows at one observation epoch.
struct ReceiverEpoch {
  std::int64_t sample_index = 0;
  double t_s = 0.0;             ///< sample time since the first sample of the source
  std::optional<GpsTime> t_rx;  ///< receiver clock (set once four transmit times exist)
  std::vector<ChannelObservation> observations;
  PvtSolution pvt;
  int channels_tracking = 0;
  /// `pvt` is a hot start's coarse-time fix: from code phases before the receiver clock was
  /// set, so no observations and no `t_rx` (its time is the fix's own, `pvt.t`).
  bool coarse_time = false;
};

/// Each observed GPS satellite's C/N0 (dB-Hz) at the epoch, by PRN.
inline std::map<int, double> cn0_by_prn(const ReceiverEpoch& epoch) {
  std::map<int, double> cn0;
  for (const ChannelObservation& o : epoch.observations)
    if (o.system == GnssSystem::gps) cn0[o.prn] = o.cn0_dbhz;
  return cn0;
}

/// Each observed satellite's C/N0 (dB-Hz) at the epoch, GPS and Galileo.
inline std::map<SatelliteId, double> cn0_by_satellite(const ReceiverEpoch& epoch) {
  std::map<SatelliteId, double> cn0;
  for (const ChannelObservation& o : epoch.observations) cn0[o.satellite()] = o.cn0_dbhz;
  return cn0;
}

/// How the receiver came to its first fix (summary.json, the run's closing line).
struct FirstFixOrigin {
  /// "cold": every satellite of the fix had its ephemeris decoded from the signal;
  /// "ephemerides given": one or more came from assistance (--ephemeris-from);
  /// "coarse-time": a hot start's fix from code phases before any time of week was decoded.
  std::string method;
  /// When four satellites first had ephemerides (s since the first sample), decoded or given.
  std::optional<double> ephemerides_complete_s;
};

class GnssReceiver {
 public:
  GnssReceiver(ReceiverConfig config, SampleSource& source);
  ~GnssReceiver();
  /// Runs to the end of the source; `on_epoch` sees every observation epoch, `on_correlation`
  /// (optional) every correlator epoch of every channel.
  void run(const std::function<void(const ReceiverEpoch&)>& on_epoch,
           const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation = {},
           const std::function<void(double)>& progress = {});
  /// Ionosphere parameters to use until the broadcast ones (subframe 4 page 18, sent once
  /// every 12.5 min) are decoded, e.g. from a navigation file given as assistance.
  void set_assisted_iono(const IonoParameters& iono);
  /// Broadcast ephemerides to use until the satellites' own are decoded (assisted start:
  /// the first fix then needs only a transmit time, i.e. one subframe, not a whole frame).
  /// Galileo records in `nav` serve the Galileo channels the same way.
  void set_assisted_ephemerides(const NavData& nav);
  /// The ephemeris in use for a PRN (decoded, else assisted), nullptr when there is none.
  const Ephemeris* ephemeris(int prn) const;
  /// Lets an outside filter steer channels through the controllers it hands out
  /// (nullptr: the channels' own loops only). Not owned. Channels with an outside
  /// controller still track on the worker threads: the filter sees them only through
  /// the BlockSnapshot after each block.
  void set_channel_aiding(ChannelAiding* aiding);
  /// Receiver clock time at an absolute sample index, once the clock is set.
  std::optional<GpsTime> receiver_time(std::int64_t sample_index) const;
  /// Sum of the steps the receiver clock has been steered by since it was set (s). An
  /// outside clock model follows the steps from this sum: differencing two receiver
  /// times instead would pick up their rounding (a GPS seconds-of-week double resolves
  /// about 0.1 ns, 3.5 cm, and those errors add up over thousands of blocks).
  double clock_steps_s() const;
  double sample_rate_hz() const;
  /// Seconds of signal the run processed: from its first sample to the end of the last
  /// block read (gaps included), 0 before the first block.
  double processed_s() const;
  /// Ephemerides in use (decoded, else assisted), ionosphere and UTC decoded so far.
  std::map<int, Ephemeris> ephemerides() const;
  /// Only those ephemerides decoded from the signal (what nav.rnx reports).
  std::map<int, Ephemeris> decoded_ephemerides() const;
  IonoParameters iono() const;
  /// The atmosphere models in use (ReceiverConfig::atmosphere): predict ranges with these
  /// and iono() so that they agree with the receiver's own PVT.
  const AtmosphereModels& atmosphere() const;
  UtcParameters utc() const;
  /// The GPS satellites acquisition found, each once, in the order first found.
  std::vector<int> acquired_prns() const;
  /// Every satellite acquisition found, GPS first, each system's in the order first found.
  std::vector<SatelliteId> acquired_satellites() const;
  /// The Galileo ephemerides decoded from the signal (by SVID) and the GGTO, if broadcast;
  /// none when the run does not track Galileo.
  std::map<int, galileo::GalileoEphemeris> decoded_galileo_ephemerides() const;
  /// The Galileo ephemerides in use at t (decoded, else assisted; by SVID), as the PVT takes
  /// them; empty when the run does not track Galileo.
  std::map<int, galileo::GalileoEphemeris> galileo_ephemerides(const GpsTime& t) const;
  std::optional<galileo::GgtoParameters> ggto() const;
  /// The systems the receiver tracks (ReceiverConfig::systems).
  const std::vector<GnssSystem>& systems() const;
  /// What the acquisition saw, for telling why it found nothing: its configuration, the
  /// latest samples it kept (a full window while a channel is free) and the strongest
  /// correlation of all its searches.
  AcquisitionEvidence acquisition_evidence() const;
  /// The full GPS week the signal broadcast (the first subframe 1 decoded, resolved against
  /// the reference), once known.
  std::optional<int> signal_week() const;
  /// How the first PVT fix was obtained, once there was one.
  std::optional<FirstFixOrigin> first_fix_origin() const;
  /// What the hot start did, when one was configured (ReceiverConfig::hot_start).
  std::optional<HotStartReport> hot_start_report() const;
  /// Per PRN, over every channel that tracked it (dropped ones included).
  std::vector<NavigationStatus> navigation_status() const;
  /// Every filter-guided search finished so far, in the order they finished.
  const std::vector<GuidedSearchRecord>& guided_searches() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepnav
