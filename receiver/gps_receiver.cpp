#include "receiver/gps_receiver.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <exception>
#include <latch>
#include <thread>

#include <algorithm>
#include <limits>
#include <chrono>
#include <cmath>
#include <set>

#include "receiver/build_date.hpp"
#include "receiver/tracking/correlator.hpp"
#include "receiver/navdata/nav_decoder.hpp"
#include "receiver/sources/sample_history.hpp"
#include "receiver/worker_threads.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

constexpr double c = gps::kSpeedOfLight_mps;

struct Channel {
  std::unique_ptr<TrackingChannel> trk;
  std::unique_ptr<ScalarChannelControl> loop;  ///< the channel's own loops
  ChannelController* steered = nullptr;         ///< an outside filter's controller (not owned), or none
  std::unique_ptr<NavDecoder> nav;
  double last_doppler_hz = 0.0;
  double start_t_s = 0.0;
  /// Started from a guided search and not confirmed yet by the filter's lock criterion:
  /// the search's record, finished when the channel is confirmed or dropped.
  std::optional<GuidedSearchRecord> guided;
  double guided_deadline_s = 0.0;
  bool aided_lock_seen = false;  ///< the filter's lock criterion held in the block just tracked
  bool drop = false;             ///< to be released after this block
};

/// A guided search under way, with the ephemeris the prediction came from.
struct ActiveSearch {
  GuidedSearch search;
  Ephemeris ephemeris;
  double started_s = 0.0;
};

}  // namespace

struct GpsReceiver::Impl {
  ReceiverConfig cfg;
  SampleSource& src;
  double fs;
  std::vector<Channel> channels;
  std::vector<int> acquired;
  std::map<int, Ephemeris> ephs;
  std::set<int> decoded_prns;  ///< PRNs whose entry in ephs came from the signal (not assistance)
  IonoParameters iono;
  UtcParameters utc;
  PvtSolver pvt;
  // Receiver time: t_rx(s) = time_ref + (s - sample_ref) / fs.
  std::optional<GpsTime> time_ref;
  std::int64_t sample_ref = 0;
  double clock_steps_s = 0.0;  ///< sum of the steers applied to time_ref
  std::int64_t first_index = -1, end_index = -1;  ///< span of the samples read so far
  bool gap_since_epoch = false;  ///< samples lost since the last observation epoch
  double last_reacquire_s = 0.0;
  ChannelAiding* aiding = nullptr;  ///< an outside filter driving channels, or none
  std::vector<int> tracked_prns;        ///< channels of the block just tracked, lost ones included
  struct EpochRecord {
    CorrelatorEpoch epoch;
    ChannelSnapshot snapshot;
    bool new_ephemeris = false;
  };
  std::vector<std::vector<EpochRecord>> records;  ///< per channel, for the block being tracked
  std::unique_ptr<WorkerThreads> pool;  ///< channel workers (ReceiverConfig::threads > 1)
  unsigned thread_count = 1;
  std::map<int, NavigationStatus> finished_status;  ///< of channels already dropped
  // Filter-guided reacquisition.
  std::vector<ActiveSearch> searches;
  std::map<int, double> guided_retry_at_s;  ///< per PRN: not searched again before this time
  double last_guided_s = -std::numeric_limits<double>::infinity();
  std::vector<GuidedSearchRecord> guided_log;

  static void add_status(std::map<int, NavigationStatus>& into, const Channel& ch) {
    NavigationStatus& s = into[ch.trk->prn()];
    s.prn = ch.trk->prn();
    s.tracked_s += ch.trk->seconds_tracked();
    s.subframes_decoded += ch.nav->subframes_decoded();
    s.parity_failures += ch.nav->parity_failures();
    s.ephemeris = s.ephemeris || ch.nav->ephemeris().has_value();
  }
  std::optional<NavData> assisted;

  // The GPS week (see ReceiverConfig::reference_week).
  struct SignalWeek {
    int week;              ///< resolved full week
    int wn10;              ///< as broadcast
    int prn;               ///< the satellite it came from
    double subframe_sow;   ///< start of that subframe 1
  };
  std::optional<SignalWeek> signal_week;
  /// A GPS time near the data that may set the clock before the signal's week is decoded
  /// (from reference_week or the assisted ephemerides), and what it came from.
  std::optional<GpsTime> reference_epoch() const {
    if (cfg.reference_week > 0) return GpsTime{cfg.reference_week, kSecondsPerWeek / 2};
    if (assisted && !assisted->ephemerides.empty()) {
      const Ephemeris& e = assisted->ephemerides.front();
      return GpsTime{e.week, e.toe_s};
    }
    return std::nullopt;
  }
  std::string reference_origin() const {
    if (cfg.reference_week > 0) return fmt::format("{} {}", cfg.reference_week_origin, cfg.reference_week);
    if (const auto r = reference_epoch())
      return fmt::format("the assisted ephemerides ({}, week {})", assisted->source.empty() ? "assistance" : assisted->source,
                         r->week);
    return fmt::format("the build date (week {})", build_time().week);
  }
  /// The week LNAV's 10-bit week numbers are resolved against.
  int resolution_week() const {
    const auto r = reference_epoch();
    return r ? r->week : build_time().week;
  }

  /// Takes the week from the first subframe 1 any channel decoded; checks it against the
  /// reference given and against the clock when that was set before.
  void take_signal_week(std::int64_t now) {
    if (signal_week) return;
    for (const Channel& ch : channels) {
      const auto& wn = ch.nav->week_number();
      if (!wn) continue;
      const int week = lnav::resolve_week(wn->wn10, resolution_week());
      signal_week = SignalWeek{week, wn->wn10, ch.trk->prn(), wn->subframe_start_sow};
      spdlog::info("GPS week {} (PRN {:2d} broadcasts week number {} modulo 1024; resolved against {})", week,
                   ch.trk->prn(), wn->wn10, reference_origin());
      const GpsTime sent{week, wn->subframe_start_sow};
      const auto contradiction = [&](double off_s) {
        return fmt::format("the GPS week of {} contradicts the signal: PRN {} broadcasts week number {} (modulo 1024), "
                           "i.e. week {} ({:.1f} days off){}",
                           reference_origin(), ch.trk->prn(), wn->wn10, week, off_s / 86400.0,
                           cfg.reference_week > 0 ? fmt::format(": give {} {} or leave it out",
                                                                cfg.reference_week_origin, week)
                                                  : std::string(": a navigation file of another day?"));
      };
      // A week either side is the data crossing a week boundary, not a contradiction.
      if (cfg.reference_week > 0 && std::abs(week - cfg.reference_week) > 1)
        throw std::runtime_error(contradiction((week - cfg.reference_week) * kSecondsPerWeek));
      if (time_ref) {
        // The clock set from the reference, now: some seconds after the subframe was sent.
        const double off_s = time_ref->plus_seconds(static_cast<double>(now - sample_ref) / fs).seconds_since(sent);
        if (std::abs(off_s) > kSecondsPerWeek / 2) throw std::runtime_error(contradiction(off_s));
      }
      return;
    }
  }

  Impl(ReceiverConfig c, SampleSource& s)
      : cfg(std::move(c)), src(s), fs(s.sample_rate_hz()), pvt(cfg.pvt, cfg.atmosphere) {
    cfg.acquisition.sample_rate_hz = fs;
    cfg.acquisition.if_hz = src.intermediate_frequency_hz();
    cfg.tracking.sample_rate_hz = fs;
    cfg.tracking.if_hz = src.intermediate_frequency_hz();
    if (!(fs >= kMinSampleRate_hz && fs <= kMaxSampleRate_hz))
      throw std::invalid_argument(fmt::format("sample rate {} Hz is outside the receiver's [{:g}, {:g}] Hz", fs,
                                              kMinSampleRate_hz, kMaxSampleRate_hz));
    if (!(std::abs(src.intermediate_frequency_hz()) < fs / 2))
      throw std::invalid_argument(fmt::format("intermediate frequency {} Hz is not below half the sample rate ({} Hz)",
                                              src.intermediate_frequency_hz(), fs / 2));
    if (!(cfg.observation_rate_hz >= 0.01 && cfg.observation_rate_hz <= 50.0))
      throw std::invalid_argument(fmt::format("observation rate {} Hz is outside [0.01, 50] Hz", cfg.observation_rate_hz));
    if (cfg.channels < 1 || cfg.channels > gps::kMaxPrn)
      throw std::invalid_argument(fmt::format("{} tracking channels: expected 1 to {}", cfg.channels, gps::kMaxPrn));
    if (cfg.reference_week < 0)
      throw std::invalid_argument(fmt::format("{} {} is negative", cfg.reference_week_origin, cfg.reference_week));
    if (cfg.threads > kMaxReceiverThreads)
      throw std::invalid_argument(fmt::format("{} channel threads asked for: at most {} (0: one per core)", cfg.threads,
                                              kMaxReceiverThreads));
    const unsigned threads = cfg.threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : cfg.threads;
    // The calling thread takes one share of the channels itself: threads - 1 workers.
    if (threads > 1) pool = std::make_unique<WorkerThreads>(threads - 1, "channel worker");
    thread_count = threads;
  }

  std::unique_ptr<Acquisition> acquisition;

  bool tracked(int prn) const {
    return std::any_of(channels.begin(), channels.end(), [&](const Channel& ch) { return ch.trk->prn() == prn; });
  }
  bool searching(int prn) const {
    return std::any_of(searches.begin(), searches.end(),
                       [&](const ActiveSearch& a) { return a.search.prediction().prn == prn; });
  }
  bool searchable(int prn) const {
    return cfg.acquisition.prns.empty() || std::count(cfg.acquisition.prns.begin(), cfg.acquisition.prns.end(), prn);
  }

  /// Searches `samples` (starting at absolute index `first`) for satellites not tracked yet.
  void acquire(const std::vector<Sample>& samples, std::int64_t first) {
    if (static_cast<int>(channels.size()) >= cfg.channels) return;
    std::vector<int> prns;
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn)
      if (!tracked(prn) && !searching(prn) && searchable(prn)) prns.push_back(prn);
    if (prns.empty()) return;
    // One search engine for the run: its plans, code spectra and buffers are made once.
    if (!acquisition) acquisition = std::make_unique<Acquisition>(cfg.acquisition);
    if (static_cast<std::int64_t>(samples.size()) < acquisition->samples_needed() / std::max(1, cfg.acquisition.noncoherent))
      return;
    auto results = acquisition->search(samples, prns);
    std::sort(results.begin(), results.end(), [](const auto& a, const auto& b) { return a.cn0_dbhz > b.cn0_dbhz; });
    for (const auto& r : results) {
      if (!r.detected || static_cast<int>(channels.size()) >= cfg.channels) continue;
      Channel ch;
      ch.trk = std::make_unique<TrackingChannel>(cfg.tracking, ChannelStart{r.prn, r.doppler_hz, r.code_phase_chips, first, 0, std::nullopt});
      ch.loop = std::make_unique<ScalarChannelControl>(r.doppler_hz, cfg.pll_order, cfg.pull_in, cfg.tracking_loops);
      if (aiding) ch.steered = aiding->controller_for(r.prn);
      ch.nav = std::make_unique<NavDecoder>(r.prn, resolution_week());
      ch.last_doppler_hz = r.doppler_hz;
      ch.start_t_s = static_cast<double>(first) / fs;
      spdlog::debug("PRN {:2d} acquired: {:.1f} Hz, {:.2f} chips, {:.1f} dB-Hz", r.prn, r.doppler_hz, r.code_phase_chips, r.cn0_dbhz);
      acquired.push_back(r.prn);
      channels.push_back(std::move(ch));
    }
  }

  ChannelView view_of(const Channel& ch) const {
    const auto eph = ephs.find(ch.trk->prn());
    return ChannelView{*ch.trk, *ch.nav, eph == ephs.end() ? nullptr : &eph->second, time_ref.has_value()};
  }

  static void carry_out(Channel& ch, const ChannelDecision& d) {
    if (d.loss_detection) ch.trk->set_loss_detection(*d.loss_detection);
    if (d.command) ch.trk->apply(*d.command);
  }

  /// What the outside filter published for its channels since they last tracked.
  void collect_published() {
    for (Channel& ch : channels)
      if (ch.steered) carry_out(ch, ch.steered->between_blocks(view_of(ch)));
  }

  /// The channels as the outside filter sees them after a block ending at `end`.
  BlockSnapshot snapshot(std::int64_t end) const {
    BlockSnapshot s;
    s.end_sample = end;
    s.sample_rate_hz = fs;
    if (time_ref) s.clock = ReceiverClockReference{*time_ref, sample_ref, fs};
    s.iono = iono;
    s.tracked_prns = tracked_prns;
    for (const Channel& ch : channels) {
      ChannelStatus c;
      c.prn = ch.trk->prn();
      c.state = ch.trk->state();
      c.bit_synced = ch.trk->bit_edge_period().has_value();
      c.decoder_synchronised = ch.nav->synchronised();
      c.cn0_dbhz = ch.trk->cn0_dbhz();
      c.replica_transmit_sow = transmit_time_sow(*ch.nav, *ch.trk, end);
      if (const auto eph = ephs.find(c.prn); eph != ephs.end()) c.ephemeris = eph->second;
      s.channels.push_back(std::move(c));
    }
    return s;
  }

  /// One channel over one block: correlation, its controller after every epoch (the
  /// outside filter's, else its own loops), navigation bits; what concerns the whole
  /// receiver is recorded for later. Touches nothing but the channel and its controllers.
  void run_channel(Channel& ch, const SampleBlock& block, std::vector<EpochRecord>& out) {
    ch.trk->process(block, [&](const CorrelatorEpoch& e) {
      const ChannelView view = view_of(ch);
      ChannelDecision outside;
      if (ch.steered) {
        outside = ch.steered->on_epoch(e, view);
        carry_out(ch, outside);
      }
      if (!outside.owns_epoch) {
        // Each epoch's command acts from the very next sample (not after the block).
        const ChannelDecision own = ch.loop->on_epoch(e, view);
        carry_out(ch, own);
        ch.last_doppler_hz = own.command->carrier_doppler_hz;
      } else {
        // Keep the loop ready to take the channel back where the outside filter leaves it.
        ch.loop->follow(e, view);
        ch.last_doppler_hz = e.carrier_doppler_hz;
      }
      // The channel assembles the data bits (sums over each bit's 20 code periods); a bit
      // completed by this epoch goes to the decoder at once.
      bool fresh = false;
      for (const PromptBit& bit : ch.trk->take_bits()) fresh = ch.nav->add_bit(bit) || fresh;
      ChannelSnapshot snap{ch.trk->prn(), ch.trk->state(), ch.trk->cn0_dbhz(), ch.nav->ephemeris().has_value(), {}};
      if (outside.owns_epoch && outside.lock) {
        snap.cn0_dbhz = outside.lock->cn0_dbhz;
        snap.aided_lock = outside.lock->locked;
        ch.aided_lock_seen = ch.aided_lock_seen || outside.lock->locked;
      }
      out.push_back({e, snap, fresh});
    });
  }

  void track(const SampleBlock& block,
             const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation) {
    records.resize(channels.size());
    for (auto& r : records) r.clear();
    tracked_prns.clear();
    for (const Channel& ch : channels) tracked_prns.push_back(ch.trk->prn());
    // Channels are independent within a block (an outside filter's controllers included:
    // each touches only its own channel): with worker threads they run in parallel.
    if (pool && channels.size() > 1) {
      // One contiguous share of the channels per thread, the calling thread's included: a
      // 10 ms block is about 0.1 ms of work, so one hand-off per thread and block, not per channel.
      const std::size_t shares = std::min<std::size_t>(thread_count, channels.size());
      const auto share = [&](std::size_t g) {
        for (std::size_t i = g * channels.size() / shares; i < (g + 1) * channels.size() / shares; ++i)
          run_channel(channels[i], block, records[i]);
      };
      std::latch done(static_cast<std::ptrdiff_t>(shares - 1));
      std::vector<std::exception_ptr> errors(shares);
      for (std::size_t g = 1; g < shares; ++g) {
        pool->post([&, g] {
          try {
            share(g);
          } catch (...) {
            errors[g] = std::current_exception();
          }
          done.count_down();
        });
      }
      try {
        share(0);
      } catch (...) {
        errors[0] = std::current_exception();
      }
      done.wait();
      for (const auto& e : errors)
        if (e) std::rethrow_exception(e);
    } else {
      for (std::size_t i = 0; i < channels.size(); ++i) run_channel(channels[i], block, records[i]);
    }
    for (std::size_t i = 0; i < channels.size(); ++i) {
      const Channel& ch = channels[i];
      for (const EpochRecord& r : records[i]) {
        if (r.new_ephemeris) {
          ephs[ch.trk->prn()] = *ch.nav->ephemeris();
          decoded_prns.insert(ch.trk->prn());
          if (ch.nav->iono().valid) iono = ch.nav->iono();
          if (ch.nav->utc().valid) utc = ch.nav->utc();
          spdlog::debug("PRN {:2d}: ephemeris IODE {}", ch.trk->prn(), ch.nav->ephemeris()->iode);
        }
        if (on_correlation) on_correlation(r.epoch, r.snapshot);
      }
    }
    settle_guided_channels(static_cast<double>(block.first_sample_index + static_cast<std::int64_t>(block.samples.size())) / fs);
    const auto lost = std::remove_if(channels.begin(), channels.end(), [&](const Channel& ch) {
      if (ch.trk->state() != ChannelState::lost && !ch.drop) return false;
      if (!ch.drop) spdlog::info("PRN {:2d}: loss of lock", ch.trk->prn());
      if (ch.steered) ch.steered->channel_ended();
      add_status(finished_status, ch);
      return true;
    });
    channels.erase(lost, channels.end());
  }

  /// Confirms the guided channels the filter's lock criterion now holds, drops those it has
  /// not held for confirm_within_s.
  void settle_guided_channels(double t) {
    for (Channel& ch : channels) {
      const bool locked = ch.aided_lock_seen;
      ch.aided_lock_seen = false;
      if (!ch.guided) continue;
      GuidedSearchRecord& rec = *ch.guided;
      if (locked) {
        rec.outcome = GuidedSearchRecord::Outcome::confirmed;
      } else if (t > ch.guided_deadline_s || ch.trk->state() == ChannelState::lost) {
        rec.outcome = GuidedSearchRecord::Outcome::dropped;
        ch.drop = true;
        guided_retry_at_s[rec.prn] = t + cfg.guided.retry_after_s;
      } else {
        continue;
      }
      rec.ended_s = t;
      spdlog::info("t = {:.2f} s: PRN {:2d}: guided channel {} ({:.1f} s after the search found it)", t, rec.prn,
                   locked ? "locked by the filter" : "not locked by the filter: dropped", t - ch.start_t_s);
      guided_log.push_back(rec);
      ch.guided.reset();
    }
  }

  /// Filter-guided reacquisition after the block ending at snap.end_sample: the searches
  /// under way take the block; finished ones start a channel or are recorded; then, every
  /// interval_s, the filter is asked where the untracked satellites are and the narrow ones
  /// searched from the next block on.
  void guide(const SampleBlock& block, const BlockSnapshot& snap) {
    const std::int64_t end = snap.end_sample;
    const double t = static_cast<double>(end) / fs;
    for (auto it = searches.begin(); it != searches.end();) {
      it->search.add(block);
      if (it->search.outcome() == GuidedSearch::Outcome::searching) {
        ++it;
        continue;
      }
      finish_search(*it, end);
      it = searches.erase(it);
    }
    if (!time_ref || t - last_guided_s < cfg.guided.interval_s) return;
    last_guided_s = t;
    if (free_for_search() <= 0) return;
    const GpsTime now = time_ref->plus_seconds(static_cast<double>(end - sample_ref) / fs);
    std::vector<UntrackedSatellite> candidates;
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn) {
      if (tracked(prn) || searching(prn) || !searchable(prn)) continue;
      if (const auto r = guided_retry_at_s.find(prn); r != guided_retry_at_s.end() && t < r->second) continue;
      if (const auto e = ephs.find(prn); e != ephs.end()) {
        candidates.push_back({prn, e->second});
      } else if (assisted) {
        if (const Ephemeris* a = assisted->select(prn, now)) candidates.push_back({prn, *a});
      }
    }
    if (candidates.empty()) return;
    std::vector<SignalPrediction> predictions = aiding->predict_untracked(snap, candidates);
    std::sort(predictions.begin(), predictions.end(),
              [](const SignalPrediction& a, const SignalPrediction& b) { return a.elevation_deg > b.elevation_deg; });
    for (const SignalPrediction& p : predictions) {
      if (free_for_search() <= 0) break;
      const auto c = std::find_if(candidates.begin(), candidates.end(), [&](const auto& u) { return u.prn == p.prn; });
      if (c == candidates.end() || p.sample != end || searching(p.prn)) continue;
      if (!GuidedSearch::is_narrow(cfg.guided.search, p)) {
        spdlog::debug("PRN {:2d}: prediction too uncertain for a guided search ({:.1f} chips, {:.1f} Hz)", p.prn,
                      p.code_sigma_chips, p.doppler_sigma_hz);
        continue;
      }
      searches.push_back({GuidedSearch(cfg.guided.search, p, fs, cfg.tracking.if_hz), c->ephemeris, t});
      spdlog::debug("t = {:.2f} s: PRN {:2d}: guided search at elevation {:.1f} deg ({} cells, {:.2f} chips / {:.1f} Hz "
                    "1-sigma)", t, p.prn,
                    p.elevation_deg, searches.back().search.cells(), p.code_sigma_chips, p.doppler_sigma_hz);
    }
  }

  int free_for_search() const {
    return std::min(cfg.channels - static_cast<int>(channels.size() + searches.size()),
                    cfg.guided.max_searches - static_cast<int>(searches.size()));
  }

  /// A finished search: a channel where it found the signal (unless that may be a tracked
  /// satellite's cross-correlation), else a retry later.
  void finish_search(const ActiveSearch& a, std::int64_t end) {
    const double t = static_cast<double>(end) / fs;
    const SignalPrediction& p = a.search.prediction();
    GuidedSearchRecord rec{p.prn, a.started_s, t, p.elevation_deg, GuidedSearchRecord::Outcome::not_found,
                           a.search.detection()};
    const auto retry_later = [&](const char* why) {
      guided_retry_at_s[p.prn] = t + cfg.guided.retry_after_s;
      spdlog::debug("t = {:.2f} s: PRN {:2d}: guided search over {:.1f} s: {}", t, p.prn, t - a.started_s, why);
      guided_log.push_back(rec);
    };
    if (!rec.detection) return retry_later("not found");
    if (static_cast<int>(channels.size()) >= cfg.channels) return retry_later("found, but no channel free");
    const GuidedStart start = a.search.start_at(end, 0);
    for (const Channel& ch : channels) {
      if (cross_correlation_suspect(start.channel.doppler_hz, rec.detection->cn0_dbhz, ch.last_doppler_hz,
                                    ch.trk->cn0_dbhz(), 2.0 * cfg.guided.search.doppler_step_hz,
                                    cfg.guided.cross_correlation_margin_db)) {
        rec.outcome = GuidedSearchRecord::Outcome::cross_correlation;
        return retry_later("rejected as a cross-correlation");
      }
    }
    Channel ch;
    ch.trk = std::make_unique<TrackingChannel>(cfg.tracking, start.channel);
    ch.loop = std::make_unique<ScalarChannelControl>(start.channel.doppler_hz, cfg.pll_order, cfg.pull_in, cfg.tracking_loops);
    ch.steered = aiding->controller_for(p.prn);
    ch.nav = std::make_unique<NavDecoder>(p.prn, resolution_week());
    ch.nav->seed_time(0, start.period0_transmit_sow);
    ch.last_doppler_hz = start.channel.doppler_hz;
    ch.start_t_s = t;
    ch.guided = rec;
    ch.guided_deadline_s = t + cfg.guided.confirm_within_s;
    // The channel's view carries the ephemeris the prediction used (as for any channel with a transmit time).
    ephs.emplace(p.prn, a.ephemeris);
    const GuidedDetection& d = *rec.detection;
    spdlog::info("t = {:.2f} s: PRN {:2d}: found by the filter-guided search ({:+.2f} chips, {:+.1f} Hz from the "
                 "prediction, {:.1f} dB-Hz after {:.1f} s)", t, p.prn, d.code_offset_chips, d.doppler_offset_hz, d.cn0_dbhz, d.dwell_s);
    acquired.push_back(p.prn);
    channels.push_back(std::move(ch));
  }

  ReceiverEpoch observe(std::int64_t s) {
    ReceiverEpoch ep;
    ep.sample_index = s;
    ep.t_s = static_cast<double>(s) / fs;
    struct Tx {
      const Channel* ch;
      double t_tx_sow;
    };
    std::vector<Tx> tx;
    for (const auto& ch : channels) {
      if (ch.trk->state() == ChannelState::tracking) ++ep.channels_tracking;
      if (!ch.nav->synchronised()) continue;
      // A guided channel's time is the filter's prediction until the filter confirms it:
      // not an observable of the receiver's own.
      if (ch.guided) continue;
      // A channel held open through a fade (by an outside filter) has a replica but no
      // signal: no observable until the signal is back.
      if (ch.trk->lock_detector().ready() && ch.trk->cn0_dbhz() < cfg.tracking.lost_cn0_dbhz) continue;
      const double chips = ch.trk->code_chips_at(s);
      const auto period = static_cast<std::int64_t>(std::floor(chips / gps::kCodeLength_chips));
      const auto t = ch.nav->transmit_time_sow(period, chips - static_cast<double>(period) * gps::kCodeLength_chips);
      if (t) tx.push_back({&ch, *t});
    }
    // The clock needs the week: the signal's own, else a reference near the data (never a
    // guess that would put a product years off).
    const std::optional<GpsTime> near =
        signal_week ? std::optional<GpsTime>(GpsTime{signal_week->week, signal_week->subframe_sow}) : reference_epoch();
    if (!time_ref && tx.size() >= 4 && near) {
      double latest = tx.front().t_tx_sow;
      for (const auto& x : tx) latest = std::max(latest, x.t_tx_sow);
      // The week of `near` or a neighbour, whichever puts the time closest to it.
      GpsTime t = GpsTime::normalized(near->week, latest + 0.068);
      const double off_s = t.seconds_since(*near);
      if (off_s > kSecondsPerWeek / 2) t.week -= 1;
      if (off_s < -kSecondsPerWeek / 2) t.week += 1;
      time_ref = t;
      sample_ref = s;
    }
    if (!time_ref) return ep;
    const GpsTime t_rx = time_ref->plus_seconds(static_cast<double>(s - sample_ref) / fs);
    ep.t_rx = t_rx;
    if (assisted) {
      for (const auto& x : tx) {
        const int prn = x.ch->trk->prn();
        if (ephs.count(prn)) continue;
        if (const Ephemeris* e = assisted->select(prn, t_rx)) ephs[prn] = *e;
      }
    }
    std::vector<PseudorangeObservation> obs;
    for (const auto& x : tx) {
      double dt = t_rx.sow - x.t_tx_sow;
      if (dt < -302400.0) dt += kSecondsPerWeek;
      if (dt > 302400.0) dt -= kSecondsPerWeek;
      ChannelObservation o;
      o.prn = x.ch->trk->prn();
      o.pseudorange_m = c * dt;
      // Doppler from the carrier phase over the last 100 ms (the loop's instantaneous
      // frequency carries its own noise); the loop frequency until that much exists.
      o.doppler_hz = x.ch->trk->mean_doppler_hz(kDopplerWindow_s).value_or(x.ch->last_doppler_hz);
      if (const auto mid = x.ch->trk->mean_doppler_mid_sample(kDopplerWindow_s))
        o.doppler_offset_s = (*mid - static_cast<double>(s)) / fs;
      o.carrier_phase_cycles = x.ch->trk->carrier_phase_cycles();
      o.cn0_dbhz = x.ch->trk->cn0_dbhz();
      o.lock_time_s = x.ch->trk->seconds_tracked();
      o.after_gap = gap_since_epoch;
      ep.observations.push_back(o);
      if (ephs.count(o.prn)) obs.push_back({o.prn, o.pseudorange_m, o.doppler_hz, o.cn0_dbhz});
    }
    ep.pvt = pvt.solve(t_rx, obs, ephs, iono);
    if (ep.pvt.valid && std::abs(ep.pvt.clock_bias_m) > 1e3) {
      // Steer the receiver clock so pseudoranges stay near the geometric ranges.
      time_ref = time_ref->plus_seconds(-ep.pvt.clock_bias_m / c);
      clock_steps_s -= ep.pvt.clock_bias_m / c;
    }
    return ep;
  }
};

GpsReceiver::GpsReceiver(ReceiverConfig config, SampleSource& source)
    : impl_(std::make_unique<Impl>(std::move(config), source)) {}
GpsReceiver::~GpsReceiver() = default;

void GpsReceiver::run(const std::function<void(const ReceiverEpoch&)>& on_epoch,
                         const std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>& on_correlation,
                         const std::function<void(double)>& progress) {
  Impl& m = *impl_;
  const auto block_samples = static_cast<std::size_t>(std::llround(m.fs / 100.0));  // 10 ms blocks
  const auto obs_step = static_cast<std::int64_t>(std::llround(m.fs / m.cfg.observation_rate_hz));
  // Cold start: acquisition over the first samples, then those samples are tracked too.
  const std::int64_t acq_samples = static_cast<std::int64_t>(std::llround(m.fs * 1e-3)) *
                                   m.cfg.acquisition.coherent_ms * m.cfg.acquisition.noncoherent;
  SampleHistory recent(static_cast<std::size_t>(acq_samples));
  SampleBlock block;
  std::int64_t next_obs = -1;
  std::int64_t expected_first = -1;
  bool first = true;
  while (m.src.read_block(block, first ? static_cast<std::size_t>(acq_samples) : block_samples)) {
    if (expected_first >= 0 && block.first_sample_index != expected_first) {
      // Samples were lost (a stream gap): the channels carry their NCOs across it, the
      // re-acquisition window restarts after it and the next observables are flagged.
      recent.clear();
      m.gap_since_epoch = true;
      // No epoch inside the gap: it has no samples. The observation grid resumes at its first
      // point at or after the samples come back (one step, however long the gap).
      if (next_obs >= 0 && next_obs < block.first_sample_index)
        next_obs += (block.first_sample_index - next_obs + obs_step - 1) / obs_step * obs_step;
      if (!m.src.gap_sizes_exact() && !m.channels.empty()) {
        // A gap known only roughly leaves every code phase off by its error: start over
        // from acquisition as soon as the window after the gap is full.
        spdlog::info("a gap of estimated size at sample {}: every channel re-acquires", block.first_sample_index);
        for (const Channel& ch : m.channels) {
          m.add_status(m.finished_status, ch);
          if (ch.steered) ch.steered->channel_ended();
        }
        m.channels.clear();
        m.searches.clear();
        m.last_reacquire_s = -std::numeric_limits<double>::infinity();
      }
    }
    expected_first = block.first_sample_index + static_cast<std::int64_t>(block.samples.size());
    if (m.first_index < 0) m.first_index = block.first_sample_index;
    m.end_index = expected_first;
    prepare_for_correlation(block);
    if (first) {
      if (const std::string problem = if_sample_problem(block.samples, m.src.is_real()); !problem.empty())
        spdlog::warn("the first {} samples: {}", block.samples.size(), problem);
      m.acquire(block.samples, block.first_sample_index);
      next_obs = block.first_sample_index + obs_step;
      first = false;
    }
    if (m.aiding) {
      m.aiding->before_block();
      m.collect_published();
    }
    m.track(block, on_correlation);
    const std::int64_t end = block.first_sample_index + static_cast<std::int64_t>(block.samples.size());
    m.take_signal_week(end);
    if (m.aiding) {
      const BlockSnapshot snap = m.snapshot(end);
      m.aiding->after_block(snap);
      m.collect_published();
      if (m.cfg.guided.enabled) m.guide(block, snap);
    }
    // Keep the last acquisition window of samples for re-acquisition, while a channel is free.
    if (static_cast<int>(m.channels.size()) < m.cfg.channels)
      recent.append(block.samples.data(), block.samples.size(), block.first_sample_index);
    else
      recent.clear();
    while (next_obs <= end) {
      on_epoch(m.observe(next_obs));
      m.gap_since_epoch = false;
      next_obs += obs_step;
    }
    const double t = static_cast<double>(end) / m.fs;
    if (t - m.last_reacquire_s >= m.cfg.reacquire_interval_s && static_cast<int>(m.channels.size()) < m.cfg.channels &&
        recent.full()) {
      m.last_reacquire_s = t;
      // The new channels start at the window's first sample, already processed: they begin
      // with the next block, carried across by their NCOs.
      m.acquire(recent.in_order(), recent.first_index());
    }
    if (progress) progress(t);
  }
  for (const auto& ch : m.channels) {
    spdlog::debug("PRN {:2d}: {} subframes decoded, {} preamble candidates failed parity, ephemeris {}", ch.trk->prn(),
                  ch.nav->subframes_decoded(), ch.nav->parity_failures(), ch.nav->ephemeris() ? "yes" : "no");
  }
}

void GpsReceiver::set_assisted_iono(const IonoParameters& iono) {
  if (!impl_->iono.valid) impl_->iono = iono;
}

void GpsReceiver::set_assisted_ephemerides(const NavData& nav) { impl_->assisted = nav; }

const Ephemeris* GpsReceiver::ephemeris(int prn) const {
  const auto it = impl_->ephs.find(prn);
  return it == impl_->ephs.end() ? nullptr : &it->second;
}

void GpsReceiver::set_channel_aiding(ChannelAiding* aiding) {
  impl_->aiding = aiding;
  for (Channel& ch : impl_->channels) ch.steered = aiding ? aiding->controller_for(ch.trk->prn()) : nullptr;
}

std::optional<GpsTime> GpsReceiver::receiver_time(std::int64_t sample_index) const {
  if (!impl_->time_ref) return std::nullopt;
  return impl_->time_ref->plus_seconds(static_cast<double>(sample_index - impl_->sample_ref) / impl_->fs);
}

double GpsReceiver::sample_rate_hz() const { return impl_->fs; }
double GpsReceiver::processed_s() const {
  return impl_->first_index < 0 ? 0.0 : static_cast<double>(impl_->end_index - impl_->first_index) / impl_->fs;
}
double GpsReceiver::clock_steps_s() const { return impl_->clock_steps_s; }

std::map<int, Ephemeris> GpsReceiver::ephemerides() const { return impl_->ephs; }

std::map<int, Ephemeris> GpsReceiver::decoded_ephemerides() const {
  std::map<int, Ephemeris> out;
  for (int prn : impl_->decoded_prns) out.emplace(prn, impl_->ephs.at(prn));
  return out;
}
IonoParameters GpsReceiver::iono() const { return impl_->iono; }
const AtmosphereModels& GpsReceiver::atmosphere() const { return impl_->cfg.atmosphere; }
UtcParameters GpsReceiver::utc() const { return impl_->utc; }
std::vector<int> GpsReceiver::acquired_prns() const { return impl_->acquired; }

std::optional<int> GpsReceiver::signal_week() const {
  if (!impl_->signal_week) return std::nullopt;
  return impl_->signal_week->week;
}

const std::vector<GuidedSearchRecord>& GpsReceiver::guided_searches() const { return impl_->guided_log; }

const char* to_string(GuidedSearchRecord::Outcome outcome) {
  switch (outcome) {
    case GuidedSearchRecord::Outcome::not_found: return "not found";
    case GuidedSearchRecord::Outcome::cross_correlation: return "cross-correlation";
    case GuidedSearchRecord::Outcome::confirmed: return "confirmed";
    case GuidedSearchRecord::Outcome::dropped: return "dropped";
  }
  return "?";
}

std::vector<NavigationStatus> GpsReceiver::navigation_status() const {
  std::map<int, NavigationStatus> all = impl_->finished_status;
  for (const auto& ch : impl_->channels) Impl::add_status(all, ch);
  std::vector<NavigationStatus> out;
  for (const auto& [prn, s] : all) out.push_back(s);
  return out;
}

}  // namespace deepnav
