#pragma once
// Filter-guided reacquisition: with an outside filter that predicts the satellites the
// receiver does not track (ChannelAiding::predict_untracked), each is searched in a narrow
// window with long integrations (GuidedSearch) and a channel started where it is found,
// its bit edges and time taken from the prediction, so that the filter steers it at once.
//
// The rules, all in GuidedReacquisitionConfig: the filter is asked every interval_s once the
// receiver clock is set; at most max_searches run at once, and no more than there are free
// channels; the highest satellites are searched first. A detection that may be a tracked
// satellite's cross-correlation is rejected. A channel started from a search must be
// confirmed by the filter's lock criterion (SignalLockReport) within confirm_within_s, else
// it is dropped. A satellite not found, rejected or dropped is searched again only after
// retry_after_s. Every search ends in a GuidedSearchRecord.
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include "receiver/acquisition/guided_search.hpp"
#include "receiver/tracking/channel_controller.hpp"
#include "signals/ephemeris.hpp"

namespace deepnav {

struct GuidedReacquisitionConfig {
  bool enabled = true;
  GuidedSearchConfig search;
  double interval_s = 1.0;     ///< how often the filter is asked for predictions
  double retry_after_s = 4.0;  ///< a satellite not found, or dropped, is searched again after this
  /// A guided channel that the filter's lock criterion (SignalLockReport) has not confirmed
  /// within this is dropped: the detection was noise or another satellite's code.
  double confirm_within_s = 8.0;
  int max_searches = 3;  ///< at once (each costs about as much as 2-3 tracking channels)
  /// A detection this far (dB) below a tracked satellite whose Doppler lies within two
  /// Doppler steps of it, modulo the code's 1 kHz lines, may be that satellite's
  /// cross-correlation and is rejected (the FFT acquisition's rule, for one candidate).
  double cross_correlation_margin_db = 18.0;
};

/// One guided search, as products and diagnostics report it.
struct GuidedSearchRecord {
  enum class Outcome { not_found, cross_correlation, confirmed, dropped };
  int prn = 0;
  double started_s = 0.0;  ///< sample time the search began
  double ended_s = 0.0;    ///< when its outcome was known (for a found signal: confirmed or dropped)
  double elevation_deg = 0.0;
  Outcome outcome = Outcome::not_found;
  std::optional<GuidedDetection> detection;
};
const char* to_string(GuidedSearchRecord::Outcome outcome);

/// A guided search under way, with the ephemeris its prediction came from.
struct GuidedSearchTask {
  GuidedSearch search;
  Ephemeris ephemeris;
  double started_s = 0.0;  ///< sample time it began
};

/// A signal the receiver tracks, as the cross-correlation rule sees it.
struct TrackedSignal {
  double doppler_hz = 0.0;
  double cn0_dbhz = 0.0;
};

/// A channel to start where a guided search found its signal.
struct GuidedChannelStart {
  GuidedStart start;
  Ephemeris ephemeris;  ///< the one the prediction came from: the channel's until its own is decoded
};

class GuidedReacquisition {
 public:
  GuidedReacquisition(GuidedReacquisitionConfig config, double sample_rate_hz, double if_hz);

  /// After a block ending at snapshot.end_sample, every interval_s once the clock is set:
  /// asks `aiding` where the satellites `untracked` lists (those not tracked that have an
  /// ephemeris at the receiver time given; called only then) lie, and starts a search for
  /// each narrow prediction for the block's end, highest first, while searches and
  /// `free_channels` (channels not in use) allow.
  void schedule(const BlockSnapshot& snapshot, int free_channels,
                const std::function<std::vector<UntrackedSatellite>(const GpsTime&)>& untracked, ChannelAiding& aiding);
  /// The searches under way take the next block; those it ended are handed back, in the
  /// order they began, for conclude().
  std::vector<GuidedSearchTask> advance(const SampleBlock& block);
  /// A search ended at sample `end`: where it found a signal and a channel is free, and the
  /// signal is not a `tracked` one's cross-correlation, the channel to start (the caller
  /// starts it; it then awaits confirmation); otherwise the search is recorded and its
  /// satellite retried later.
  std::optional<GuidedChannelStart> conclude(const GuidedSearchTask& ended, std::int64_t end, int free_channels,
                                             const std::vector<TrackedSignal>& tracked);
  /// After each block (at time t_s), for every channel in channel order: whether the filter's
  /// lock criterion held in the block, and whether the channel lost lock. Confirms a channel
  /// awaiting confirmation that the filter locked; returns true when it must be dropped (not
  /// locked within confirm_within_s, or lost).
  bool settle(int prn, bool locked_by_filter, bool lost, double t_s);
  /// Samples were lost and every channel released: the searches and the channels awaiting
  /// confirmation end without a record.
  void abandon();

  bool searching(int prn) const;
  /// A channel started from a search and not yet confirmed: its time is the filter's
  /// prediction, not an observable of the receiver's own.
  bool awaiting_confirmation(int prn) const { return unconfirmed_.count(prn) > 0; }
  int searches_under_way() const { return static_cast<int>(searches_.size()); }
  /// Every search finished so far, in the order they finished.
  const std::vector<GuidedSearchRecord>& records() const { return records_; }

 private:
  /// Searches that may start now, with `free_channels` channels not in use.
  int free_for_search(int free_channels) const;
  bool waiting_to_retry(int prn, double t_s) const;
  void retry_later(const GuidedSearchRecord& record, const char* why);

  /// A channel started from a search, until the filter confirms or drops it.
  struct Unconfirmed {
    GuidedSearchRecord record;
    double channel_start_s = 0.0;
    double deadline_s = 0.0;
  };

  GuidedReacquisitionConfig cfg_;
  double fs_, if_hz_;
  std::vector<GuidedSearchTask> searches_;
  std::map<int, Unconfirmed> unconfirmed_;  ///< by PRN
  std::map<int, double> retry_at_s_;        ///< per PRN: not searched again before this time
  double last_asked_s_ = -std::numeric_limits<double>::infinity();
  std::vector<GuidedSearchRecord> records_;
};

}  // namespace deepnav
