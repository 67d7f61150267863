#include "receiver/gnss_receiver.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "receiver/acquisition/acquisition_schedule.hpp"
#include "receiver/navdata/broadcast_navigation.hpp"
#include "receiver/receiver_clock.hpp"
#include "receiver/tracking/correlator.hpp"
#include "receiver/worker_threads.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

/// The configuration checked against the source, with the source's sample rate and IF.
ReceiverConfig checked(ReceiverConfig cfg, const SampleSource& src) {
  const double fs = src.sample_rate_hz();
  const double if_hz = src.intermediate_frequency_hz();
  cfg.acquisition.sample_rate_hz = fs;
  cfg.acquisition.if_hz = if_hz;
  cfg.tracking.sample_rate_hz = fs;
  cfg.tracking.if_hz = if_hz;
  if (!(fs >= kMinSampleRate_hz && fs <= kMaxSampleRate_hz))
    throw std::invalid_argument(fmt::format("sample rate {} Hz is outside the receiver's [{:g}, {:g}] Hz", fs,
                                            kMinSampleRate_hz, kMaxSampleRate_hz));
  if (!(std::abs(if_hz) < fs / 2))
    throw std::invalid_argument(
        fmt::format("intermediate frequency {} Hz is not below half the sample rate ({} Hz)", if_hz, fs / 2));
  if (!(cfg.observation_rate_hz >= 0.01 && cfg.observation_rate_hz <= 50.0))
    throw std::invalid_argument(
        fmt::format("observation rate {} Hz is outside [0.01, 50] Hz", cfg.observation_rate_hz));
  if (cfg.channels < 1 || cfg.channels > gps::kMaxPrn)
    throw std::invalid_argument(fmt::format("{} tracking channels: expected 1 to {}", cfg.channels, gps::kMaxPrn));
  if (cfg.systems.empty()) throw std::invalid_argument("no satellite system to track: expected GPS, Galileo or both");
  for (auto it = cfg.systems.begin(); it != cfg.systems.end(); ++it)
    if (std::find(std::next(it), cfg.systems.end(), *it) != cfg.systems.end())
      throw std::invalid_argument(fmt::format("satellite system {} is listed twice", system_name(*it)));
  return cfg;
}

/// The workers that track channels besides the calling thread, which takes one share of
/// the channels itself: `threads` - 1 of them (none for one thread).
std::unique_ptr<WorkerThreads> channel_workers(unsigned threads) {
  if (threads > kMaxReceiverThreads)
    throw std::invalid_argument(
        fmt::format("{} channel threads asked for: at most {} (0: one per core)", threads, kMaxReceiverThreads));
  const unsigned n = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
  return n > 1 ? std::make_unique<WorkerThreads>(n - 1, "channel worker") : nullptr;
}

/// The observation epochs: every `step` samples from the run's first sample on. No epoch
/// lies inside a gap in the samples (it has none): the grid resumes at its first point at
/// or after the samples come back, one step however long the gap.
class EpochGrid {
 public:
  explicit EpochGrid(std::int64_t step) : step_(step) {}
  void start(std::int64_t first_sample) { next_ = first_sample + step_; }
  void resume_at(std::int64_t sample) {
    if (next_ >= 0 && next_ < sample) next_ += (sample - next_ + step_ - 1) / step_ * step_;
  }
  /// The next epoch, when it lies at or before `end`; the grid then moves past it.
  std::optional<std::int64_t> next_until(std::int64_t end) {
    if (next_ < 0 || next_ > end) return std::nullopt;
    const std::int64_t epoch = next_;
    next_ += step_;
    return epoch;
  }

 private:
  std::int64_t step_;
  std::int64_t next_ = -1;
};

}  // namespace

struct GnssReceiver::Impl {
  ReceiverConfig cfg;
  SampleSource& src;
  double fs;
  ChannelLoopSettings loops;
  ReceiverClock clock;
  std::unique_ptr<WorkerThreads> workers;  ///< channel workers (ReceiverConfig::threads > 1)
  AcquisitionSchedule acquisition;
  GuidedReacquisition guided;
  BroadcastNavigation navigation;
  PvtSolver pvt;
  ChannelAiding* aiding = nullptr;  ///< an outside filter driving channels, or none
  std::vector<ReceiverChannel> channels;
  std::vector<std::vector<ChannelEpochRecord>> records;  ///< per channel, for the block being tracked
  std::vector<int> tracked_prns;                         ///< channels of the block just tracked, lost ones included
  std::vector<int> tracked_galileo_svids;                ///< the same for the Galileo channels
  std::vector<int> acquired;                             ///< PRNs, each once, in the order first acquired
  std::map<int, NavigationStatus> finished_status;       ///< of channels already released
  std::int64_t first_index = -1, end_index = -1;         ///< span of the samples read so far
  bool gap_since_epoch = false;                          ///< samples lost since the last observation epoch
  std::optional<double> ephemerides_complete_s;          ///< four satellites first had ephemerides
  std::optional<FirstFixOrigin> first_fix;
  std::optional<HotStart> hot_start;               ///< ReceiverConfig::hot_start, until the clock is set
  bool gps_on;                                     ///< GPS is tracked
  std::unique_ptr<GalileoChannelSet> galileo;      ///< when Galileo is tracked
  std::optional<Eigen::Vector3d> last_fix_ecef_m;  ///< the latest valid fix's position

  Impl(ReceiverConfig c, SampleSource& s)
      : cfg(checked(std::move(c), s)),
        src(s),
        fs(s.sample_rate_hz()),
        loops{cfg.tracking, cfg.pll_order, cfg.pull_in, cfg.tracking_loops},
        clock(fs, cfg.reference_week, cfg.reference_week_origin),
        workers(channel_workers(cfg.threads)),
        acquisition(cfg.acquisition, cfg.reacquire_interval_s),
        guided(cfg.guided, fs, cfg.tracking.if_hz),
        pvt(cfg.pvt, cfg.atmosphere) {
    if (cfg.hot_start) hot_start.emplace(*cfg.hot_start, fs, cfg.atmosphere);
    gps_on = includes_system(cfg.systems, GnssSystem::gps);
    if (includes_system(cfg.systems, GnssSystem::galileo))
      galileo = std::make_unique<GalileoChannelSet>(cfg.galileo, fs, cfg.tracking.if_hz);
  }

  int free_channels() const { return cfg.channels - static_cast<int>(channels.size()); }
  bool channel_free() const { return free_channels() > 0; }
  bool tracked(int prn) const {
    return std::any_of(channels.begin(), channels.end(), [&](const ReceiverChannel& ch) { return ch.prn() == prn; });
  }

  ReceiverChannel& start_channel(const ChannelStart& start) {
    // The satellites found, in the order first found: a satellite acquired again (after a
    // gap, a loss of lock) is still one satellite.
    if (std::find(acquired.begin(), acquired.end(), start.prn) == acquired.end()) acquired.push_back(start.prn);
    return channels.emplace_back(loops, start, aiding ? aiding->controller_for(start.prn) : nullptr,
                                 clock.resolution_week());
  }

  /// Whatever the channel leaves behind when it is released.
  void end_channel(const ReceiverChannel& ch) {
    ch.add_to(finished_status[ch.prn()]);
    if (ch.steered()) ch.steered()->channel_ended();
  }

  /// Searches `samples` (starting at absolute index `first`) for satellites neither tracked
  /// nor under a guided search, and starts a channel on each found, strongest first.
  void acquire(const std::vector<Sample>& samples, std::int64_t first) {
    if (!gps_on || !channel_free()) return;
    std::vector<int> prns;
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn)
      if (!tracked(prn) && !guided.searching(prn) && acquisition.searchable(prn)) prns.push_back(prn);
    if (prns.empty()) return;
    for (const AcquisitionResult& r : acquisition.search(samples, prns)) {
      if (!channel_free()) break;
      spdlog::debug("PRN {:2d} acquired: {:.1f} Hz, {:.2f} chips, {:.1f} dB-Hz", r.prn, r.doppler_hz,
                    r.code_phase_chips, r.cn0_dbhz);
      start_channel(ChannelStart{r.prn, r.doppler_hz, r.code_phase_chips, first, 0, std::nullopt});
    }
  }

  /// The run's first samples: a cold start.
  void cold_start(const SampleBlock& block) {
    if (const std::string problem = if_sample_problem(block.samples, src.is_real()); !problem.empty())
      spdlog::warn("the first {} samples: {}", block.samples.size(), problem);
    acquire(block.samples, block.first_sample_index);
  }

  /// Samples were lost before this block (a stream gap): the channels carry their NCOs
  /// across it, the re-acquisition window restarts after it and the next observables are
  /// flagged.
  void after_gap(std::int64_t first_after) {
    acquisition.restart_window();
    if (galileo) galileo->restart_window();
    gap_since_epoch = true;
    if (src.gap_sizes_exact() || channels.empty()) return;
    // A gap known only roughly leaves every code phase off by its error: start over from
    // acquisition as soon as the window after the gap is full.
    spdlog::info("a gap of estimated size at sample {}: every channel re-acquires", first_after);
    for (const ReceiverChannel& ch : channels) end_channel(ch);
    channels.clear();
    if (galileo) galileo->release_all();
    guided.abandon();
    acquisition.search_when_full();
  }

  /// What the outside filter published for its channels since they last tracked.
  void collect_published(std::int64_t next_sample) {
    for (ReceiverChannel& ch : channels) ch.collect_published(navigation.ephemeris(ch.prn()), clock.is_set());
    if (galileo) galileo->collect_published(clock.at(next_sample));
  }

  /// Every channel over one block (in parallel on the worker threads: channels are
  /// independent within a block, an outside filter's controllers included), then what
  /// concerns the whole receiver: ephemerides decoded, correlator epochs reported, guided
  /// channels settled, lost channels released.
  void track(const SampleBlock& block,
             const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation) {
    records.resize(channels.size());
    for (auto& r : records) r.clear();
    tracked_prns.clear();
    for (const ReceiverChannel& ch : channels) tracked_prns.push_back(ch.prn());
    tracked_galileo_svids.clear();
    const std::size_t galileo_channels = galileo ? galileo->size() : 0;
    for (std::size_t k = 0; k < galileo_channels; ++k) tracked_galileo_svids.push_back(galileo->channel(k).svid());
    const bool clock_set = clock.is_set();
    const std::optional<GpsTime> t_block = clock.at(block.first_sample_index);
    run_in_shares(workers.get(), channels.size() + galileo_channels, [&](std::size_t i) {
      if (i >= channels.size()) {
        GalileoChannel& ch = galileo->channel(i - channels.size());
        ch.track(block, t_block ? galileo->ephemeris(ch.svid(), *t_block) : nullptr, clock_set);
        return;
      }
      channels[i].track(block, navigation.ephemeris(channels[i].prn()), clock_set, records[i]);
    });
    if (galileo && galileo->after_block()) note_ephemerides(block_end(block));
    for (std::size_t i = 0; i < channels.size(); ++i) {
      for (const ChannelEpochRecord& r : records[i]) {
        if (r.new_ephemeris) {
          navigation.take_decoded(channels[i].prn(), channels[i].decoder());
          note_ephemerides(r.epoch.first_sample + r.epoch.samples);
        }
        if (on_correlation) on_correlation(r.epoch, r.snapshot);
      }
    }
    settle_guided_channels(static_cast<double>(block_end(block)) / fs);
    release_lost_channels();
  }

  /// Records when four satellites first have ephemerides in use (`sample`: now).
  void note_ephemerides(std::int64_t sample) {
    std::size_t count = navigation.in_use().size();
    if (galileo) count += clock.is_set() ? galileo->in_use(*clock.at(sample)).size() : galileo->decoded().size();
    if (!ephemerides_complete_s && count >= kTransmitTimesToSetClock)
      ephemerides_complete_s = static_cast<double>(sample) / fs;
  }

  /// The first fix: decoded ephemerides only (cold) or some given.
  void note_first_fix(const PvtSolution& fix, bool coarse_time) {
    if (first_fix || !fix.valid) return;
    if (coarse_time) {
      first_fix = FirstFixOrigin{"coarse-time", ephemerides_complete_s};
      return;
    }
    const std::map<int, Ephemeris> decoded = navigation.decoded();
    const bool cold = std::all_of(fix.used_satellites.begin(), fix.used_satellites.end(), [&](const SatelliteId& s) {
      if (s.system == GnssSystem::galileo) return galileo && galileo->decoded().count(s.prn) > 0;
      return decoded.count(s.prn) > 0;
    });
    first_fix = FirstFixOrigin{cold ? "cold" : "ephemerides given", ephemerides_complete_s};
  }

  /// Where and when the receiver is at sample `s`, once it has a fix and a clock.
  std::optional<SkyViewPoint> sky_view(std::int64_t s) const {
    const auto t = clock.at(s);
    if (!t || !last_fix_ecef_m) return std::nullopt;
    return SkyViewPoint{*t, *last_fix_ecef_m};
  }

  static std::int64_t block_end(const SampleBlock& block) {
    return block.first_sample_index + static_cast<std::int64_t>(block.samples.size());
  }

  /// Confirms the guided channels the filter's lock criterion now holds; marks for release
  /// those it has not held in time.
  void settle_guided_channels(double t_s) {
    for (ReceiverChannel& ch : channels) {
      const bool locked = ch.take_aided_lock();
      if (guided.settle(ch.prn(), locked, ch.tracking().state() == ChannelState::lost, t_s)) ch.release();
    }
  }

  void release_lost_channels() {
    const auto gone = [](const ReceiverChannel& ch) {
      return ch.tracking().state() == ChannelState::lost || ch.released();
    };
    for (const ReceiverChannel& ch : channels) {
      if (!gone(ch)) continue;
      if (!ch.released()) spdlog::info("PRN {:2d}: loss of lock", ch.prn());
      end_channel(ch);
    }
    std::erase_if(channels, gone);
  }

  /// The week from the first subframe 1 any GPS channel decoded, or the first I/NAV page
  /// with a GST week, whichever came first.
  void take_signal_week(std::int64_t now) {
    if (clock.signal_week()) return;
    for (const ReceiverChannel& ch : channels) {
      if (const auto& wn = ch.decoder().week_number()) {
        clock.take_broadcast_week(ch.prn(), wn->wn10, wn->subframe_start_sow, now);
        return;
      }
    }
    if (!galileo) return;
    if (const auto mark = galileo->week_mark()) clock.take_galileo_week(mark->svid, mark->gst_week, mark->tow_s, now);
  }

  /// The channels as the outside filter sees them after a block ending at `end`.
  BlockSnapshot snapshot(std::int64_t end) const {
    BlockSnapshot s;
    s.end_sample = end;
    s.sample_rate_hz = fs;
    s.clock = clock.reference();
    s.iono = navigation.iono();
    s.tracked_prns = tracked_prns;
    for (const ReceiverChannel& ch : channels) {
      ChannelStatus c;
      c.prn = ch.prn();
      c.state = ch.tracking().state();
      c.bit_synced = ch.tracking().bit_edge_period().has_value();
      c.decoder_synchronised = ch.decoder().synchronised();
      c.cn0_dbhz = ch.tracking().cn0_dbhz();
      c.replica_transmit_sow = ch.transmit_time_sow(end);
      if (const Ephemeris* e = navigation.ephemeris(c.prn)) c.ephemeris = *e;
      s.channels.push_back(std::move(c));
    }
    s.tracked_galileo_svids = tracked_galileo_svids;
    if (!galileo) return s;
    const std::optional<GpsTime> t_end = clock.at(end);
    for (std::size_t k = 0; k < galileo->size(); ++k) {
      const GalileoChannel& ch = galileo->channel(k);
      E1ChannelStatus c;
      c.svid = ch.svid();
      c.state = ch.tracking().state();
      c.time_mark = ch.decoder().navigation().time_mark().has_value();
      c.cn0_dbhz = ch.cn0_dbhz();
      c.replica_transmit_sow = ch.transmit_time_sow(end);
      if (const galileo::GalileoEphemeris* e = t_end ? galileo->ephemeris(c.svid, *t_end) : nullptr) c.ephemeris = *e;
      s.galileo_channels.push_back(std::move(c));
    }
    return s;
  }

  /// Filter-guided reacquisition after the block ending at snap.end_sample: the searches
  /// under way take the block, those ended start a channel or are recorded, and new ones
  /// are scheduled.
  void guide(const SampleBlock& block, const BlockSnapshot& snap) {
    for (const GuidedSearchTask& ended : guided.advance(block)) {
      if (const auto start = guided.conclude(ended, snap.end_sample, free_channels(), tracked_signals()))
        start_guided_channel(*start);
    }
    guided.schedule(
        snap, free_channels(), [&](const GpsTime& now) { return untracked_satellites(now); }, *aiding);
  }

  std::vector<TrackedSignal> tracked_signals() const {
    std::vector<TrackedSignal> out;
    for (const ReceiverChannel& ch : channels) out.push_back({ch.last_doppler_hz(), ch.tracking().cn0_dbhz()});
    return out;
  }

  /// The satellites the acquisition may search that no channel tracks, with the ephemeris
  /// in use for each (decoded, else assisted at `now`); those without one are left out.
  std::vector<UntrackedSatellite> untracked_satellites(const GpsTime& now) const {
    std::vector<UntrackedSatellite> out;
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn) {
      if (tracked(prn) || !acquisition.searchable(prn)) continue;
      if (auto e = navigation.available(prn, now)) out.push_back({prn, std::move(*e)});
    }
    return out;
  }

  void start_guided_channel(const GuidedChannelStart& s) {
    // The channel's view carries the ephemeris the prediction used (as for any channel with
    // a transmit time).
    navigation.adopt(s.start.channel.prn, s.ephemeris);
    start_channel(s.start.channel).seed_transmit_time(s.start.period0_transmit_sow);
  }

  /// A channel observable at an epoch: its transmit time known, and its own (not a guided
  /// channel's prediction awaiting the filter's confirmation), and a signal behind it (not a
  /// replica an outside filter holds open through a fade).
  bool observable(const ReceiverChannel& ch) const {
    if (!ch.decoder().synchronised() || guided.awaiting_confirmation(ch.prn())) return false;
    return !(ch.tracking().lock_detector().ready() && ch.tracking().cn0_dbhz() < cfg.tracking.lost_cn0_dbhz);
  }

  /// A channel whose code phase a coarse-time fix may take: past pull-in, its code loop
  /// locked and its C/N0 measured above the loss threshold.
  bool code_phase_usable(const ReceiverChannel& ch) const {
    const TrackingChannel& t = ch.tracking();
    if (t.state() != ChannelState::bit_sync && t.state() != ChannelState::tracking) return false;
    if (guided.awaiting_confirmation(ch.prn())) return false;
    return t.lock_detector().ready() && t.lock_detector().code_locked() && t.cn0_dbhz() >= cfg.tracking.lost_cn0_dbhz;
  }

  /// The hot start's coarse-time fix at sample `s` (the clock is not set yet).
  void hot_start_fix(std::int64_t s, ReceiverEpoch& ep) {
    const GpsTime t_hint = hot_start->time_hint_at(s);
    std::vector<SnapshotMeasurement> measurements;
    std::map<int, Ephemeris> ephemerides;
    for (const ReceiverChannel& ch : channels) {
      if (!code_phase_usable(ch)) continue;
      auto e = navigation.available(ch.prn(), t_hint);
      if (!e) continue;
      const double chips = ch.tracking().code_chips_at(s);
      double phase = chips - std::floor(chips / gps::kCodeLength_chips) * gps::kCodeLength_chips;
      if (!(phase < gps::kCodeLength_chips)) phase = 0.0;  // rounding at the period's end
      measurements.push_back({ch.prn(), phase, ch.last_doppler_hz(), ch.tracking().cn0_dbhz()});
      ephemerides.emplace(ch.prn(), std::move(*e));
    }
    const int attempts_before = hot_start->report().attempts;
    ep.pvt = hot_start->solve(measurements, ephemerides, navigation.iono(), s);
    ep.coarse_time = true;
    // The first refusal is worth a word (a wrong hint); the next ones say the same.
    if (attempts_before == 0 && hot_start->report().attempts == 1 && !ep.pvt.valid)
      spdlog::warn("t = {:.2f} s: {}; the first fix waits for the broadcast time of week", ep.t_s, ep.pvt.reason);
    note_first_fix(ep.pvt, true);
  }

  /// Observables and PVT at sample `s`, common to all channels.
  ReceiverEpoch observe(std::int64_t s) {
    ReceiverEpoch ep;
    ep.sample_index = s;
    ep.t_s = static_cast<double>(s) / fs;
    std::vector<const ReceiverChannel*> sent;
    std::vector<double> transmit_sow;
    for (const ReceiverChannel& ch : channels) {
      if (ch.tracking().state() == ChannelState::tracking) ++ep.channels_tracking;
      if (!observable(ch)) continue;
      if (const auto t = ch.transmit_time_sow(s)) {
        sent.push_back(&ch);
        transmit_sow.push_back(*t);
      }
    }
    // Galileo transmit times are GST, tens of nanoseconds from GPS time: as good for setting
    // the clock (its first error is the travel time's, milliseconds).
    std::vector<const GalileoChannel*> galileo_sent;
    std::vector<double> galileo_transmit_sow;
    for (std::size_t i = 0; galileo && i < galileo->size(); ++i) {
      const GalileoChannel& ch = galileo->channel(i);
      if (ch.tracking().state() == E1ChannelState::tracking) ++ep.channels_tracking;
      if (!ch.observable(cfg.galileo.tracking.lost_cn0_dbhz)) continue;
      if (const auto t = ch.transmit_time_sow(s)) {
        galileo_sent.push_back(&ch);
        galileo_transmit_sow.push_back(*t);
      }
    }
    std::vector<double> all_transmit_sow = transmit_sow;
    all_transmit_sow.insert(all_transmit_sow.end(), galileo_transmit_sow.begin(), galileo_transmit_sow.end());
    clock.set_from_transmit_times(all_transmit_sow, s);
    ep.t_rx = clock.at(s);
    if (!ep.t_rx) {
      if (hot_start) hot_start_fix(s, ep);
      return ep;
    }
    for (const ReceiverChannel* ch : sent) navigation.adopt_assisted(ch->prn(), *ep.t_rx);
    note_ephemerides(s);
    std::vector<PseudorangeObservation> ranging;
    for (std::size_t k = 0; k < sent.size(); ++k) {
      const ChannelObservation o = sent[k]->observe(*ep.t_rx, transmit_sow[k], s, fs, gap_since_epoch);
      ep.observations.push_back(o);
      // The navigation data holds GPS ephemerides: a channel of another system ranges once
      // its ephemerides are kept there too.
      if (o.system == GnssSystem::gps && navigation.ephemeris(o.prn))
        ranging.push_back({o.prn, o.pseudorange_m, o.doppler_hz, o.cn0_dbhz, o.system});
    }
    if (!galileo) {
      ep.pvt = pvt.solve(*ep.t_rx, ranging, navigation.in_use(), navigation.iono());
    } else {
      const std::map<int, galileo::GalileoEphemeris> galileo_ephemerides = galileo->in_use(*ep.t_rx);
      for (std::size_t k = 0; k < galileo_sent.size(); ++k) {
        const ChannelObservation o =
            galileo_sent[k]->observe(*ep.t_rx, galileo_transmit_sow[k], s, fs, gap_since_epoch);
        ep.observations.push_back(o);
        if (galileo_ephemerides.count(o.prn))
          ranging.push_back({o.prn, o.pseudorange_m, o.doppler_hz, o.cn0_dbhz, o.system});
      }
      ep.pvt = pvt.solve(*ep.t_rx, ranging, navigation.in_use(), galileo_ephemerides, navigation.iono());
    }
    note_first_fix(ep.pvt, false);
    // Steer the receiver clock so that pseudoranges stay near the geometric ranges.
    if (ep.pvt.valid) clock.steer(ep.pvt.clock_bias_m);
    if (ep.pvt.valid) last_fix_ecef_m = ep.pvt.r_ecef_m;
    return ep;
  }
};

GnssReceiver::GnssReceiver(ReceiverConfig config, SampleSource& source)
    : impl_(std::make_unique<Impl>(std::move(config), source)) {}
GnssReceiver::~GnssReceiver() = default;

void GnssReceiver::run(const std::function<void(const ReceiverEpoch&)>& on_epoch,
                       const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation,
                       const std::function<void(double)>& progress) {
  Impl& m = *impl_;
  const auto block_samples = static_cast<std::size_t>(std::llround(m.fs / 100.0));  // 10 ms blocks
  EpochGrid epochs(static_cast<std::int64_t>(std::llround(m.fs / m.cfg.observation_rate_hz)));
  SampleBlock block;
  bool first = true;
  // The first read is one acquisition window: searched, then tracked like any block.
  while (m.src.read_block(block, first ? m.acquisition.window_samples() : block_samples)) {
    if (m.end_index >= 0 && block.first_sample_index != m.end_index) {
      m.after_gap(block.first_sample_index);
      epochs.resume_at(block.first_sample_index);
    }
    const std::int64_t end = Impl::block_end(block);
    if (m.first_index < 0) m.first_index = block.first_sample_index;
    m.end_index = end;
    prepare_for_correlation(block);
    if (first) {
      m.cold_start(block);
      epochs.start(block.first_sample_index);
      first = false;
    }
    if (m.aiding) {
      m.aiding->before_block();
      m.collect_published(block.first_sample_index);
    }
    m.track(block, on_correlation);
    m.take_signal_week(end);
    if (m.aiding) {
      const BlockSnapshot snap = m.snapshot(end);
      m.aiding->after_block(snap);
      m.collect_published(end);
      if (m.cfg.guided.enabled) m.guide(block, snap);
    }
    m.acquisition.keep(block, m.gps_on && m.channel_free());
    if (m.galileo) m.galileo->keep(block);
    while (const auto epoch = epochs.next_until(end)) {
      on_epoch(m.observe(*epoch));
      m.gap_since_epoch = false;
    }
    const double t = static_cast<double>(end) / m.fs;
    // New channels start at the window's first sample, already processed: they begin with
    // the next block, carried across by their NCOs.
    if (m.acquisition.reacquisition_due(t, m.gps_on && m.channel_free()))
      m.acquire(m.acquisition.window().in_order(), m.acquisition.window().first_index());
    if (m.galileo) m.galileo->acquire_if_due(t, m.sky_view(end));
    if (progress) progress(t);
  }
  for (const ReceiverChannel& ch : m.channels) {
    spdlog::debug("PRN {:2d}: {} subframes decoded, {} preamble candidates failed parity, ephemeris {}", ch.prn(),
                  ch.decoder().subframes_decoded(), ch.decoder().parity_failures(),
                  ch.decoder().ephemeris() ? "yes" : "no");
  }
}

void GnssReceiver::set_assisted_iono(const IonoParameters& iono) { impl_->navigation.set_assisted_iono(iono); }

void GnssReceiver::set_assisted_ephemerides(const NavData& nav) {
  impl_->navigation.set_assisted(nav);
  if (impl_->galileo) impl_->galileo->set_assisted(nav);
  impl_->clock.use_assisted_ephemerides(nav);
}

const Ephemeris* GnssReceiver::ephemeris(int prn) const { return impl_->navigation.ephemeris(prn); }

void GnssReceiver::set_channel_aiding(ChannelAiding* aiding) {
  impl_->aiding = aiding;
  if (impl_->galileo) impl_->galileo->set_channel_aiding(aiding);
  for (ReceiverChannel& ch : impl_->channels) ch.set_steered(aiding ? aiding->controller_for(ch.prn()) : nullptr);
}

std::optional<GpsTime> GnssReceiver::receiver_time(std::int64_t sample_index) const {
  return impl_->clock.at(sample_index);
}

double GnssReceiver::sample_rate_hz() const { return impl_->fs; }
double GnssReceiver::processed_s() const {
  return impl_->first_index < 0 ? 0.0 : static_cast<double>(impl_->end_index - impl_->first_index) / impl_->fs;
}
double GnssReceiver::clock_steps_s() const { return impl_->clock.steps_s(); }

std::map<int, Ephemeris> GnssReceiver::ephemerides() const { return impl_->navigation.in_use(); }
std::map<int, Ephemeris> GnssReceiver::decoded_ephemerides() const { return impl_->navigation.decoded(); }
IonoParameters GnssReceiver::iono() const { return impl_->navigation.iono(); }
const AtmosphereModels& GnssReceiver::atmosphere() const { return impl_->cfg.atmosphere; }
UtcParameters GnssReceiver::utc() const { return impl_->navigation.utc(); }
std::vector<int> GnssReceiver::acquired_prns() const { return impl_->acquired; }
std::vector<SatelliteId> GnssReceiver::acquired_satellites() const {
  std::vector<SatelliteId> out;
  for (int prn : impl_->acquired) out.push_back({GnssSystem::gps, prn});
  if (impl_->galileo)
    for (int svid : impl_->galileo->acquired()) out.push_back({GnssSystem::galileo, svid});
  return out;
}
std::map<int, galileo::GalileoEphemeris> GnssReceiver::decoded_galileo_ephemerides() const {
  if (!impl_->galileo) return {};
  return impl_->galileo->decoded();
}
std::map<int, galileo::GalileoEphemeris> GnssReceiver::galileo_ephemerides(const GpsTime& t) const {
  if (!impl_->galileo) return {};
  return impl_->galileo->in_use(t);
}
std::optional<galileo::GgtoParameters> GnssReceiver::ggto() const {
  if (!impl_->galileo) return std::nullopt;
  return impl_->galileo->ggto();
}
const std::vector<GnssSystem>& GnssReceiver::systems() const { return impl_->cfg.systems; }
AcquisitionEvidence GnssReceiver::acquisition_evidence() const {
  const AcquisitionSchedule& a = impl_->acquisition;
  return {a.config(), a.window().in_order(), a.strongest()};
}
std::optional<int> GnssReceiver::signal_week() const { return impl_->clock.signal_week(); }
std::optional<FirstFixOrigin> GnssReceiver::first_fix_origin() const { return impl_->first_fix; }
std::optional<HotStartReport> GnssReceiver::hot_start_report() const {
  if (!impl_->hot_start) return std::nullopt;
  return impl_->hot_start->report();
}

const std::vector<GuidedSearchRecord>& GnssReceiver::guided_searches() const { return impl_->guided.records(); }

std::vector<NavigationStatus> GnssReceiver::navigation_status() const {
  std::map<int, NavigationStatus> all = impl_->finished_status;
  for (const ReceiverChannel& ch : impl_->channels) ch.add_to(all[ch.prn()]);
  std::vector<NavigationStatus> out;
  for (const auto& [prn, s] : all) out.push_back(s);
  return out;
}

}  // namespace deepnav
