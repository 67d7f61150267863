#pragma once
// The figures of a jamming point's run against the synthesizer's truth, over the jammed
// window: when each satellite is tracked (ChannelTimeline), each satellite's figures and
// the solutions' error and availability. The run hands its products to a JamRecorder.
#include <Eigen/Core>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "receiver/products/product_sink.hpp"
#include "receiver/tracking/tracking_channel.hpp"
#include "signals/satellite_id.hpp"
#include "tools/bench/jam_judge.hpp"

namespace deepnav::bench {

/// One correlator integration of the run (a GPS channel's), or one observation epoch of a
/// Galileo channel (its E1 channel reports observables only: observable means tracking on
/// the pilot above the loss threshold, the scalar loss rule's verdict, or, while the filter
/// steers it, a measurement within the last second, the aided lock criterion).
struct TrackingRow {
  double t_s;  ///< start of the integration (first sample / fs), or of the epoch's interval
  SatelliteId satellite;
  ChannelState state;
  double integration_s, doppler_hz, cn0_dbhz;
  std::optional<bool> aided_lock;  ///< steered channel: the aided lock criterion
};

/// One solution of the run.
struct SolutionRow {
  double t_s;
  Eigen::Vector3d r_ecef_m;
  double lat_rad, lon_rad;
  std::string mode;
};

/// Keeps what the figures need from the run (a jam point is tens of seconds long).
class JamRecorder : public ProductSink {
 public:
  explicit JamRecorder(double fs_hz) : fs_hz_(fs_hz) {}
  void on_epoch(const NavigationEpoch& e) override;
  void on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) override;
  std::vector<TrackingRow> tracking;
  std::vector<SolutionRow> solutions;

 private:
  double fs_hz_;
  std::optional<double> last_epoch_t_s_;
};

/// When each satellite is tracked in the jammed window, from the run's integrations and
/// the synthesizer's sat_truth.csv (true Doppler, 10 Hz). An integration counts as tracked
/// when the channel is in the tracking state, its carrier is within 10 Hz of the true
/// Doppler, and its C/N0 estimate has not stayed below the receiver's loss threshold (22
/// dB-Hz) for the receiver's loss time (1 s): the rule by which scalar tracking drops a
/// channel. A channel the ultra-tight filter steers is judged by the aided lock criterion
/// instead (a measurement within the last second: an integration whose signal is detected
/// and whose code discriminator noise is no worse than at 18 dB-Hz over 10 ms), since its
/// long integrations measure below 22 dB-Hz; the aided modes hold channels open without
/// signal (their NCOs then follow the INS, so the carrier stays near the true Doppler
/// regardless), which neither rule counts.
struct ChannelTimeline {
  struct Span {
    double t_s, integration_s, cn0_dbhz;
    bool tracked;      ///< under the receiver's loss rule (22 dB-Hz for 1 s)
    bool with_signal;  ///< following, with a mean C/N0 over the last second above the signal floor
  };
  std::map<SatelliteId, std::vector<Span>> spans;  ///< per satellite, in time order; the truth's only
  std::vector<SatelliteId> satellites;             ///< every satellite the synthesizer transmitted

  /// Satellites whose latest integration starting in [t - 1 s, t) is tracked.
  int tracked_at(double t) const;
};

/// `systems`: those the receiver tracked; the truth's satellites of other systems are left out.
ChannelTimeline channel_timeline(const std::vector<TrackingRow>& tracking, const std::string& sat_truth_path,
                                 double window_start_s, double window_end_s,
                                 const std::vector<GnssSystem>& systems = {GnssSystem::gps});

/// Per-satellite tracked and signal fractions and mean C/N0 estimate in the jammed window.
JamChannels channel_figures(const ChannelTimeline& timeline, double window_start_s, double window_end_s);

/// The solutions' horizontal/vertical error against truth.csv and their availability in
/// the jammed window (a GNSS fix: not in INS coast, four satellites tracked in `timeline`).
JamSolutionFigures solution_figures(const std::vector<SolutionRow>& solutions, const std::string& truth_path,
                                    const ChannelTimeline& timeline, double window_start_s, double window_end_s);

/// As point.json records them (a figure that does not exist is null).
nlohmann::json to_json(const JamChannels& channels);
nlohmann::json to_json(const JamSolutionFigures& solution);

}  // namespace deepnav::bench
