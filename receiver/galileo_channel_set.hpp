#pragma once
// The receiver's Galileo E1 OS side: the channels, the acquisition that starts them (on the
// first samples of the run, then every reacquire interval over the latest window while a
// channel is free), the navigation data their I/NAV pages carry (ephemerides decoded, else
// given as assistance; the GGTO) and the GST week, for the receiver clock. GnssReceiver
// owns one when the run tracks Galileo, beside its GPS channels, on the same samples.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "receiver/acquisition/galileo_acquisition.hpp"
#include "receiver/galileo_channel.hpp"
#include "receiver/sources/sample_history.hpp"
#include "signals/galileo/galileo_ephemeris.hpp"
#include "signals/galileo/gst.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

struct GalileoReceiverSettings {
  int channels = 8;
  /// A full search costs some 50 ms of CPU per SVID at 4 Msps (36 SVIDs): less often than GPS's.
  double reacquire_interval_s = 10.0;
  GalileoAcquisitionConfig acquisition;  ///< sample rate and IF are taken from the source
  E1TrackingConfig tracking;             ///< sample rate and IF are taken from the source
  E1LoopSettings loops;
};

/// Where and when the receiver is (its latest fix), for predicting which satellites are up.
struct SkyViewPoint {
  GpsTime t{};
  Eigen::Vector3d r_ecef_m = Eigen::Vector3d::Zero();
};

/// The GST week the first page with one carried: what dates the receiver clock's week.
struct GalileoWeekMark {
  int svid = 0;
  int gst_week = 0;
  double tow_s = 0.0;  ///< GST time of week at the start of that page
};

class GalileoChannelSet {
 public:
  /// Throws std::invalid_argument when the sample rate is below kGalileoMinSampleRate_hz or
  /// a setting is out of range (naming it).
  GalileoChannelSet(GalileoReceiverSettings settings, double sample_rate_hz, double if_hz);
  ~GalileoChannelSet();
  GalileoChannelSet(const GalileoChannelSet&) = delete;
  GalileoChannelSet& operator=(const GalileoChannelSet&) = delete;

  bool channel_free() const { return static_cast<int>(channels_.size()) < cfg_.channels; }
  /// An outside filter that may steer the channels (ultra-tight), or none; channels started
  /// from now on ask it for their controller.
  void set_channel_aiding(ChannelAiding* aiding) { aiding_ = aiding; }

  /// The block just read joins the search window while a channel is free.
  void keep(const SampleBlock& block);
  /// Samples were lost: the window starts over after the gap.
  void restart_window() { window_.clear(); }
  /// Releases every channel (a gap of unknown size left their code phases unknown) and
  /// searches again as soon as the window is full.
  void release_all();
  /// Searches the window when a search is due at `t_s` (the first as soon as the window is
  /// full, then every reacquire interval while a channel is free) and starts a channel on
  /// every satellite found that no channel tracks, strongest first. With `where` (a fix) and
  /// assisted Galileo records, only the untracked satellites they put above the horizon
  /// there are searched (no search when there is none); otherwise every SVID.
  void acquire_if_due(double t_s, const std::optional<SkyViewPoint>& where = std::nullopt);

  std::size_t size() const { return channels_.size(); }
  GalileoChannel& channel(std::size_t i) { return *channels_[i]; }
  const GalileoChannel& channel(std::size_t i) const { return *channels_[i]; }
  /// Between blocks: what the outside filter published for the channels, each shown its
  /// ephemeris in use at `t` (none without a receiver clock).
  void collect_published(const std::optional<GpsTime>& t);
  /// After every channel tracked a block: takes the ephemerides and GGTO the pages
  /// completed, releases lost channels. Returns whether a new ephemeris came in.
  bool after_block();

  /// Galileo data sets given as assistance (a RINEX 3 navigation file's E records).
  void set_assisted(const NavData& nav);
  /// The ephemeris in use for `svid` at `t` (GPS time): decoded, else assisted; nullptr
  /// when there is none.
  const galileo::GalileoEphemeris* ephemeris(int svid, const GpsTime& t) const;
  /// Those in use at `t` for every tracked satellite, by SVID.
  std::map<int, galileo::GalileoEphemeris> in_use(const GpsTime& t) const;
  /// Those decoded from the signal (the latest per SVID).
  const std::map<int, galileo::GalileoEphemeris>& decoded() const { return decoded_; }
  std::optional<galileo::GgtoParameters> ggto() const { return ggto_; }
  /// The first GST week any channel decoded, once one did.
  std::optional<GalileoWeekMark> week_mark() const;
  /// The SVIDs acquisition found, each once, in the order first found.
  const std::vector<int>& acquired() const { return acquired_; }

 private:
  void start_channel(const GalileoAcquisitionResult& r, std::int64_t first_sample);
  /// The SVIDs to search: those predicted up at `where`, else all the untracked ones.
  std::vector<int> candidates(const std::optional<SkyViewPoint>& where) const;
  bool tracked(int svid) const;

  GalileoReceiverSettings cfg_;
  std::unique_ptr<GalileoAcquisition> search_;  ///< its plans and code spectra made once, at construction
  SampleHistory window_;
  double last_search_s_;
  std::vector<std::unique_ptr<GalileoChannel>> channels_;
  ChannelAiding* aiding_ = nullptr;
  std::map<int, galileo::GalileoEphemeris> decoded_;
  std::optional<galileo::GgtoParameters> ggto_;
  NavData assisted_;
  std::vector<int> acquired_;
};

}  // namespace deepnav
