#pragma once
// The scalar receiver: cold-start acquisition, one TrackingChannel per satellite
// steered by its own ScalarLoopController, navigation data, observables at common
// receiver epochs, and PVT. Lost channels are released and their satellites searched
// again every few seconds.
//
// Receiver time: once four channels carry a transmit time, the clock is set to the
// latest transmit time plus 68 ms at that sample and then advances with the sample
// count; after every fix it is steered by the estimated bias, so pseudoranges keep
// within a few metres of the clock bias the solution reports.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "receiver/acquisition.hpp"
#include "receiver/pvt_solver.hpp"
#include "receiver/sample_source.hpp"
#include "receiver/tracking_channel.hpp"
#include "receiver/tracking_loops.hpp"

namespace deepnav {

struct ReceiverConfig {
  int channels = 12;
  double observation_rate_hz = 1.0;     ///< up to 50
  int reference_week = 0;               ///< resolves LNAV's 10-bit week (0: today's week)
  double reacquire_interval_s = 5.0;
  AcquisitionConfig acquisition;        ///< sample rate and IF are taken from the source
  TrackingConfig tracking;
  LoopBandwidths pull_in{15.0, 10.0, 1.0, 0.5};
  LoopBandwidths tracking_loops{10.0, 0.0, 0.5, 0.5};
  PvtConfig pvt;
};

struct ChannelObservation {
  int prn = 0;
  double pseudorange_m = 0.0;
  double doppler_hz = 0.0;
  double carrier_phase_cycles = 0.0;
  double cn0_dbhz = 0.0;
  double lock_time_s = 0.0;
};

/// Everything the receiver knows at one observation epoch.
struct ReceiverEpoch {
  std::int64_t sample_index = 0;
  double t_s = 0.0;                     ///< sample time since the first sample of the source
  std::optional<GpsTime> t_rx;          ///< receiver clock (set once four transmit times exist)
  std::vector<ChannelObservation> observations;
  PvtSolution pvt;
  int channels_tracking = 0;
};

struct ChannelSnapshot {
  int prn;
  ChannelState state;
  double cn0_dbhz;
  bool has_ephemeris;
};

class ScalarReceiver {
 public:
  ScalarReceiver(ReceiverConfig config, SampleSource& source);
  ~ScalarReceiver();
  /// Runs to the end of the source; `on_epoch` sees every observation epoch, `on_epochs`
  /// (optional) every correlator epoch of every channel.
  void run(const std::function<void(const ReceiverEpoch&)>& on_epoch,
           const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation = {},
           const std::function<void(double)>& progress = {});
  /// Ionosphere parameters to use until the broadcast ones (subframe 4 page 18, sent once
  /// every 12.5 min) are decoded, e.g. from a navigation file given as assistance.
  void set_assisted_iono(const IonoParameters& iono);
  /// Ephemerides, ionosphere and UTC decoded so far.
  std::map<int, Ephemeris> ephemerides() const;
  IonoParameters iono() const;
  UtcParameters utc() const;
  std::vector<int> acquired_prns() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deepnav
