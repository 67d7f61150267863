#include "receiver/receiver_clock.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "receiver/build_date.hpp"
#include "signals/gps_constants.hpp"
#include "signals/lnav_message.hpp"

namespace deepnav {

ReceiverClock::ReceiverClock(double sample_rate_hz, int reference_week, std::string reference_week_origin)
    : fs_(sample_rate_hz), reference_week_(reference_week), reference_week_origin_(std::move(reference_week_origin)) {
  if (reference_week_ < 0)
    throw std::invalid_argument(fmt::format("{} {} is negative", reference_week_origin_, reference_week_));
}

void ReceiverClock::use_assisted_ephemerides(const NavData& nav) {
  assisted_epoch_.reset();
  if (!nav.ephemerides.empty()) {
    const Ephemeris& e = nav.ephemerides.front();
    assisted_epoch_ = GpsTime{e.week, e.toe_s};
  }
  assisted_source_ = nav.source.empty() ? "assistance" : nav.source;
}

std::optional<ReceiverClock::NearEpoch> ReceiverClock::near_epoch(double transmit_sow) const {
  if (signal_week_) return NearEpoch{GpsTime{signal_week_->week, signal_week_->subframe_start_sow}, "the signal"};
  if (assisted_epoch_)
    return NearEpoch{*assisted_epoch_,
                     fmt::format("the assisted ephemerides ({}, week {})", assisted_source_, assisted_epoch_->week)};
  if (reference_week_ > 0) {
    const double to_boundary_s = std::min(transmit_sow, kSecondsPerWeek - transmit_sow);
    if (std::abs(to_boundary_s) < kWeekBoundaryMargin_s) return std::nullopt;  // either side: wait for the signal
    return NearEpoch{GpsTime{reference_week_, kSecondsPerWeek / 2},
                     fmt::format("{} {}", reference_week_origin_, reference_week_)};
  }
  return std::nullopt;
}

std::string ReceiverClock::reference_origin() const {
  if (reference_week_ > 0) return fmt::format("{} {}", reference_week_origin_, reference_week_);
  if (assisted_epoch_)
    return fmt::format("the assisted ephemerides ({}, week {})", assisted_source_, assisted_epoch_->week);
  return fmt::format("the build date (week {})", build_time().week);
}

int ReceiverClock::resolution_week() const {
  if (reference_week_ > 0) return reference_week_;
  if (assisted_epoch_) return assisted_epoch_->week;
  return build_time().week;
}

std::string ReceiverClock::contradiction_advice(double off_s) const {
  if (!clock_from_reference_week_) return ": a navigation file of another day?";
  // The week the clock should have had where it was set: the data's week there.
  const int data_week = reference_->reference.week - static_cast<int>(std::lround(off_s / kSecondsPerWeek));
  return fmt::format(": the data is in week {} where the clock was set; give {} {} or leave it out", data_week,
                     reference_week_origin_, data_week);
}

void ReceiverClock::take_broadcast_week(int prn, int wn10, double subframe_start_sow, std::int64_t now) {
  if (signal_week_) return;
  const int week = lnav::resolve_week(wn10, resolution_week());
  spdlog::info("GPS week {} (PRN {:2d} broadcasts week number {} modulo 1024; resolved against {})", week, prn, wn10,
               reference_origin());
  take_signal_week(week, subframe_start_sow, fmt::format("PRN {} broadcasts week number {} (modulo 1024)", prn, wn10),
                   now);
}

void ReceiverClock::take_galileo_week(int svid, int gst_week, double page_start_tow_s, std::int64_t now) {
  if (signal_week_) return;
  // GST week 0 began where GPS week 1024 did; the 12 bits broadcast last until GST week 4095.
  const int week = gst_week + 1024;
  spdlog::info("GPS week {} (E{:02d} broadcasts GST week {})", week, svid, gst_week);
  take_signal_week(week, page_start_tow_s, fmt::format("E{:02d} broadcasts GST week {}", svid, gst_week), now);
}

void ReceiverClock::take_signal_week(int week, double start_sow, const std::string& broadcast, std::int64_t now) {
  signal_week_ = SignalWeek{week, start_sow};
  // A week either side is the data crossing a week boundary, not a contradiction.
  if (reference_week_ > 0 && std::abs(week - reference_week_) > 1)
    throw std::runtime_error(fmt::format(
        "the GPS week of {} contradicts the signal: {}, i.e. week {} ({:.1f} days off): give {} {} or leave it out",
        reference_origin(), broadcast, week, (week - reference_week_) * kSecondsPerWeek / 86400.0,
        reference_week_origin_, week));
  if (reference_) {
    // The clock, dated before this message came, now: some seconds after it was sent.
    const double off_s = reference_->at(now).seconds_since(GpsTime{week, start_sow});
    if (std::abs(off_s) > kSecondsPerWeek / 2)
      throw std::runtime_error(fmt::format(
          "the GPS week of {} contradicts the signal: {} in a message sent at second {:.0f} of its week, i.e. week "
          "{}, {:.1f} days from the receiver clock it dated{}",
          clock_origin_, broadcast, start_sow, week, off_s / 86400.0, contradiction_advice(off_s)));
  }
}

std::optional<int> ReceiverClock::signal_week() const {
  if (!signal_week_) return std::nullopt;
  return signal_week_->week;
}

void ReceiverClock::set_from_transmit_times(const std::vector<double>& transmit_sow, std::int64_t sample) {
  if (reference_ || transmit_sow.size() < kTransmitTimesToSetClock) return;
  const double latest = *std::max_element(transmit_sow.begin(), transmit_sow.end());
  // The clock needs the week: the signal's own, else a time near the data (never a guess
  // that would put a product years, or a week, off).
  const std::optional<NearEpoch> near = near_epoch(latest);
  if (!near) return;
  // The week of `near` or a neighbour, whichever puts the time closest to it.
  GpsTime t = GpsTime::normalized(near->t.week, latest + kInitialTravelTime_s);
  const double off_s = t.seconds_since(near->t);
  if (off_s > kSecondsPerWeek / 2) t.week -= 1;
  if (off_s < -kSecondsPerWeek / 2) t.week += 1;
  reference_ = ReceiverClockReference{t, sample, fs_};
  clock_origin_ = near->origin;
  clock_from_reference_week_ = !signal_week_ && !assisted_epoch_;
}

void ReceiverClock::steer(double clock_bias_m) {
  if (!reference_ || !(std::abs(clock_bias_m) > kClockSteerAbove_m)) return;
  const double step_s = -clock_bias_m / gps::kSpeedOfLight_mps;
  reference_->reference = reference_->reference.plus_seconds(step_s);
  steps_s_ += step_s;
}

std::optional<GpsTime> ReceiverClock::at(std::int64_t sample) const {
  if (!reference_) return std::nullopt;
  return reference_->at(sample);
}

}  // namespace deepnav
