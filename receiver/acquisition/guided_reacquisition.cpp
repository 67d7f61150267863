#include "receiver/acquisition/guided_reacquisition.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace deepnav {

const char* to_string(GuidedSearchRecord::Outcome outcome) {
  switch (outcome) {
    case GuidedSearchRecord::Outcome::not_found:
      return "not found";
    case GuidedSearchRecord::Outcome::cross_correlation:
      return "cross-correlation";
    case GuidedSearchRecord::Outcome::confirmed:
      return "confirmed";
    case GuidedSearchRecord::Outcome::dropped:
      return "dropped";
  }
  return "?";
}

GuidedReacquisition::GuidedReacquisition(GuidedReacquisitionConfig config, double sample_rate_hz, double if_hz)
    : cfg_(std::move(config)), fs_(sample_rate_hz), if_hz_(if_hz) {}

bool GuidedReacquisition::searching(int prn) const {
  return std::any_of(searches_.begin(), searches_.end(),
                     [&](const GuidedSearchTask& a) { return a.search.prediction().prn == prn; });
}

int GuidedReacquisition::free_for_search(int free_channels) const {
  const int under_way = searches_under_way();
  return std::min(free_channels - under_way, cfg_.max_searches - under_way);
}

bool GuidedReacquisition::waiting_to_retry(int prn, double t_s) const {
  const auto r = retry_at_s_.find(prn);
  return r != retry_at_s_.end() && t_s < r->second;
}

void GuidedReacquisition::schedule(const BlockSnapshot& snapshot, int free_channels,
                                   const std::function<std::vector<UntrackedSatellite>(const GpsTime&)>& untracked,
                                   ChannelAiding& aiding) {
  const std::int64_t end = snapshot.end_sample;
  const double t = static_cast<double>(end) / fs_;
  if (!snapshot.clock || t - last_asked_s_ < cfg_.interval_s) return;
  last_asked_s_ = t;
  if (free_for_search(free_channels) <= 0) return;
  std::vector<UntrackedSatellite> candidates = untracked(snapshot.clock->at(end));
  std::erase_if(candidates,
                [&](const UntrackedSatellite& u) { return searching(u.prn) || waiting_to_retry(u.prn, t); });
  if (candidates.empty()) return;
  std::vector<SignalPrediction> predictions = aiding.predict_untracked(snapshot, candidates);
  std::sort(predictions.begin(), predictions.end(),
            [](const SignalPrediction& a, const SignalPrediction& b) { return a.elevation_deg > b.elevation_deg; });
  for (const SignalPrediction& p : predictions) {
    if (free_for_search(free_channels) <= 0) break;
    const auto c = std::find_if(candidates.begin(), candidates.end(), [&](const auto& u) { return u.prn == p.prn; });
    if (c == candidates.end() || p.sample != end || searching(p.prn)) continue;
    if (!GuidedSearch::is_narrow(cfg_.search, p)) {
      spdlog::debug("PRN {:2d}: prediction too uncertain for a guided search ({:.1f} chips, {:.1f} Hz)", p.prn,
                    p.code_sigma_chips, p.doppler_sigma_hz);
      continue;
    }
    searches_.push_back({GuidedSearch(cfg_.search, p, fs_, if_hz_), c->ephemeris, t});
    spdlog::debug(
        "t = {:.2f} s: PRN {:2d}: guided search at elevation {:.1f} deg ({} cells, {:.2f} chips / {:.1f} Hz "
        "1-sigma)",
        t, p.prn, p.elevation_deg, searches_.back().search.cells(), p.code_sigma_chips, p.doppler_sigma_hz);
  }
}

std::vector<GuidedSearchTask> GuidedReacquisition::advance(const SampleBlock& block) {
  std::vector<GuidedSearchTask> ended;
  for (auto it = searches_.begin(); it != searches_.end();) {
    it->search.add(block);
    if (it->search.outcome() == GuidedSearch::Outcome::searching) {
      ++it;
      continue;
    }
    ended.push_back(std::move(*it));
    it = searches_.erase(it);
  }
  return ended;
}

void GuidedReacquisition::retry_later(const GuidedSearchRecord& record, const char* why) {
  retry_at_s_[record.prn] = record.ended_s + cfg_.retry_after_s;
  spdlog::debug("t = {:.2f} s: PRN {:2d}: guided search over {:.1f} s: {}", record.ended_s, record.prn,
                record.ended_s - record.started_s, why);
  records_.push_back(record);
}

std::optional<GuidedChannelStart> GuidedReacquisition::conclude(const GuidedSearchTask& ended, std::int64_t end,
                                                                int free_channels,
                                                                const std::vector<TrackedSignal>& tracked) {
  const double t = static_cast<double>(end) / fs_;
  const SignalPrediction& p = ended.search.prediction();
  GuidedSearchRecord rec{
      p.prn, ended.started_s, t, p.elevation_deg, GuidedSearchRecord::Outcome::not_found, ended.search.detection()};
  if (!rec.detection) {
    retry_later(rec, "not found");
    return std::nullopt;
  }
  if (free_channels <= 0) {
    retry_later(rec, "found, but no channel free");
    return std::nullopt;
  }
  const GuidedStart start = ended.search.start_at(end, 0);
  const double window_hz = 2.0 * cfg_.search.doppler_step_hz;
  for (const TrackedSignal& s : tracked) {
    if (cross_correlation_suspect(start.channel.doppler_hz, rec.detection->cn0_dbhz, s.doppler_hz, s.cn0_dbhz,
                                  window_hz, cfg_.cross_correlation_margin_db)) {
      rec.outcome = GuidedSearchRecord::Outcome::cross_correlation;
      retry_later(rec, "rejected as a cross-correlation");
      return std::nullopt;
    }
  }
  const GuidedDetection& d = *rec.detection;
  spdlog::info(
      "t = {:.2f} s: PRN {:2d}: found by the filter-guided search ({:+.2f} chips, {:+.1f} Hz from the "
      "prediction, {:.1f} dB-Hz after {:.1f} s)",
      t, p.prn, d.code_offset_chips, d.doppler_offset_hz, d.cn0_dbhz, d.dwell_s);
  unconfirmed_[p.prn] = Unconfirmed{rec, t, t + cfg_.confirm_within_s};
  return GuidedChannelStart{start, ended.ephemeris};
}

bool GuidedReacquisition::settle(int prn, bool locked_by_filter, bool lost, double t_s) {
  const auto it = unconfirmed_.find(prn);
  if (it == unconfirmed_.end()) return false;
  Unconfirmed& u = it->second;
  bool drop = false;
  if (locked_by_filter) {
    u.record.outcome = GuidedSearchRecord::Outcome::confirmed;
  } else if (t_s > u.deadline_s || lost) {
    u.record.outcome = GuidedSearchRecord::Outcome::dropped;
    drop = true;
    retry_at_s_[prn] = t_s + cfg_.retry_after_s;
  } else {
    return false;
  }
  u.record.ended_s = t_s;
  spdlog::info("t = {:.2f} s: PRN {:2d}: guided channel {} ({:.1f} s after the search found it)", t_s, prn,
               locked_by_filter ? "locked by the filter" : "not locked by the filter: dropped",
               t_s - u.channel_start_s);
  records_.push_back(u.record);
  unconfirmed_.erase(it);
  return drop;
}

void GuidedReacquisition::abandon() {
  searches_.clear();
  unconfirmed_.clear();
}

}  // namespace deepnav
