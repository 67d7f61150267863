#pragma once
// The receiver clock and the GPS week it runs in.
//
// The clock: once four channels carry a transmit time, it is set at that sample to the
// latest transmit time plus 68 ms (a typical travel time from a satellite, so that the first
// pseudoranges are near the ranges), and then advances with the sample count:
// t_rx(s) = reference + (s - reference_sample) / fs. After a fix it is steered by the
// estimated bias, so that pseudoranges keep near the geometric ranges.
//
// The week: the signal broadcasts it modulo 1024 (LNAV's 10-bit WN, in subframe 1: the
// week that subframe is sent in), so a week near the data resolves it: the reference week
// given (ReceiverConfig::reference_week), else the epoch of the assisted ephemerides, else
// the build date (data within about ten years of it). Before the first subframe 1 the clock
// takes its week from a time near the data: the assisted ephemerides' epoch (toe, hours
// from the data), else the reference week (the week the data starts in) — but not within
// kWeekBoundaryMargin_s of a week boundary, where the data may lie on either side of it —
// and is checked against that subframe when it comes; from the build date alone, or near a
// boundary, it waits for that subframe, so that no product carries a guessed week.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "receiver/tracking/channel_controller.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

/// Travel time of the signal the clock is set with (about 20,000 km).
inline constexpr double kInitialTravelTime_s = 0.068;
/// A fix's clock bias beyond this (3.3 us) steers the clock; a smaller one is left to the
/// solution's clock estimate.
inline constexpr double kClockSteerAbove_m = 1e3;
/// Transmit times (channels) the clock is set with.
inline constexpr std::size_t kTransmitTimesToSetClock = 4;
/// Within this of a week boundary a reference week alone does not date the transmit times
/// (the data may have begun before the boundary and reached the clock after it, or a week
/// named after the data's end): the clock waits for the signal's week (subframe 1 comes
/// every 30 s).
inline constexpr double kWeekBoundaryMargin_s = 3600.0;

class ReceiverClock {
 public:
  /// `reference_week`: a GPS week near the data (0: none), named `reference_week_origin` in
  /// messages; a negative one is std::invalid_argument.
  ReceiverClock(double sample_rate_hz, int reference_week, std::string reference_week_origin);

  /// Assisted ephemerides: without a reference week, the first one's epoch is the week
  /// near the data (replacing what an earlier call gave).
  void use_assisted_ephemerides(const NavData& nav);
  /// The week LNAV's 10-bit week numbers are resolved against.
  int resolution_week() const;

  /// The first subframe 1 decoded: `prn` broadcast week number `wn10` in the subframe that
  /// began at `subframe_start_sow`, decoded by sample `now`. Resolves the full week and
  /// checks it against the reference week and against the clock when that was set before;
  /// a contradiction is std::runtime_error naming what set the clock and the week the data
  /// is in. Later calls are ignored: the first subframe 1 decides.
  void take_broadcast_week(int prn, int wn10, double subframe_start_sow, std::int64_t now);
  /// The same for the first Galileo I/NAV page with a GST week (`gst_week`, 12 bits, full
  /// until 2078) from `svid`, the page starting at GST second `page_start_tow_s`: GPS week =
  /// GST week + 1024. Whichever system's week comes first decides.
  void take_galileo_week(int svid, int gst_week, double page_start_tow_s, std::int64_t now);
  /// The full week the signal broadcast, once take_broadcast_week() has run.
  std::optional<int> signal_week() const;

  /// Sets the clock at `sample` from the channels' transmit times (seconds of week) there,
  /// once there are four and a time near the data is known (the signal's week, else the
  /// assisted ephemerides' epoch, else the reference week away from a week boundary); does
  /// nothing when the clock is already set.
  void set_from_transmit_times(const std::vector<double>& transmit_sow, std::int64_t sample);
  /// After a fix: steps the clock by the bias it estimated (m), when that exceeds
  /// kClockSteerAbove_m.
  void steer(double clock_bias_m);

  bool is_set() const { return reference_.has_value(); }
  /// Receiver time at an absolute sample index, once the clock is set.
  std::optional<GpsTime> at(std::int64_t sample) const;
  /// The clock's reference, once set.
  const std::optional<ReceiverClockReference>& reference() const { return reference_; }
  /// Sum of the steps the clock has been steered by since it was set (s).
  double steps_s() const { return steps_s_; }

 private:
  /// A GPS time near the data (and what it came from) that may date `transmit_sow` before
  /// the signal's week is decoded; nullopt when none may.
  struct NearEpoch {
    GpsTime t;
    std::string origin;
  };
  std::optional<NearEpoch> near_epoch(double transmit_sow) const;
  /// Takes the full week the signal broadcast (`broadcast`: who said what, for messages) in
  /// a message starting at `start_sow`, decoded by sample `now`, and checks it.
  void take_signal_week(int week, double start_sow, const std::string& broadcast, std::int64_t now);
  /// What the week 10-bit week numbers are resolved against came from, for messages.
  std::string reference_origin() const;
  /// The advice for a clock that the signal's week contradicts by `off_s`.
  std::string contradiction_advice(double off_s) const;

  struct SignalWeek {
    int week = 0;                     ///< resolved full week
    double subframe_start_sow = 0.0;  ///< start of the subframe 1 it came from
  };

  double fs_;
  int reference_week_;
  std::string reference_week_origin_;
  std::optional<GpsTime> assisted_epoch_;  ///< the first assisted ephemeris's week and toe
  std::string assisted_source_;
  std::optional<SignalWeek> signal_week_;
  std::optional<ReceiverClockReference> reference_;
  std::string clock_origin_;  ///< what dated the clock when it was set
  bool clock_from_reference_week_ = false;
  double steps_s_ = 0.0;
};

}  // namespace deepnav
