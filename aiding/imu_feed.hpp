#pragma once
// An IMU log handed to a navigator in time order, with where it has no data: its gaps (an
// interval the reader found too long: ins/imu_file.hpp, ins/imu_log_reader.hpp) and its
// end. Both aided navigators take their IMU through it (aided_receiver.hpp at each block
// of IF samples, recorded_fusion.hpp at each observation epoch), and both stop the INS
// where the log has no data, starting it again from the fixes after a gap: a state
// propagated on increments that no longer describe the motion is not a solution, whatever
// the satellites say after it.
//
// A gap is reached once the time is past its last sample by more than 1.5 nominal
// intervals, or as soon as the first sample after it is due (a gap that lies wholly
// between two calls); the end, once the time is past the last sample by as much.
#include <cstddef>
#include <functional>
#include <string>

#include "ins/imu_file.hpp"

namespace deepnav::aiding {

class ImuFeed {
 public:
  /// `log` must outlive the feed.
  explicit ImuFeed(const ImuLog& log);

  /// Hands every sample up to `t_s` to `take`, in order; `on_gap` is called for each gap
  /// reached (before the samples after it), `on_end` once, when the log has ended before
  /// `t_s`.
  void advance(double t_s, const std::function<void(const ImuSample&)>& take,
               const std::function<void(const ImuGap&)>& on_gap, const std::function<void()>& on_end);

  /// Whether the log has data at the last time advanced to: not inside a gap, not past its
  /// end (an INS may start there).
  bool covers() const { return !in_gap_ && !ended_; }
  bool ended() const { return ended_; }
  /// The time of the last sample handed over (-inf before the first).
  double last_sample_t_s() const { return last_t_s_; }

  /// "IMU data missing from t = A s to B s (FILE line N)", for the navigators' messages;
  /// the times from `origin_s` on the log's axis.
  std::string describe(const ImuGap& gap, double origin_s = 0.0) const;

 private:
  const ImuLog& log_;
  double margin_s_;  ///< past a gap's start or the log's end by this much: reached
  std::size_t next_sample_ = 0, next_gap_ = 0;
  bool in_gap_ = false, ended_ = false;
  double gap_end_t_s_ = 0.0;
  double last_t_s_;
};

}  // namespace deepnav::aiding
