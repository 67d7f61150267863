#include "receiver/galileo_channel_set.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ins/frames.hpp"
#include "signals/galileo/galileo_constants.hpp"

namespace deepnav {
namespace {

/// The settings with the source's sample rate and IF, checked.
GalileoReceiverSettings checked(GalileoReceiverSettings s, double fs, double if_hz) {
  if (fs < kGalileoMinSampleRate_hz)
    throw std::invalid_argument(fmt::format(
        "Galileo E1 needs at least {:g} Msps (BOC(1,1)'s main lobes span +-2 MHz); the source gives {:g} Msps",
        kGalileoMinSampleRate_hz / 1e6, fs / 1e6));
  if (s.channels < 1 || s.channels > kGalileoMaxSvid)
    throw std::invalid_argument(fmt::format("{} Galileo channels: expected 1 to {}", s.channels, kGalileoMaxSvid));
  if (!(s.reacquire_interval_s > 0.0))
    throw std::invalid_argument(
        fmt::format("Galileo reacquire interval {} s: expected a positive number", s.reacquire_interval_s));
  // Subchip edges all at one place between samples: the sampled BOC(1,1) correlation moves in
  // steps and the code loop reads them (docs/receiver.md, "Sample rate").
  const double subchips_per_sample = fs / (2.0 * galileo::kE1CodeRate_cps);
  if (std::abs(subchips_per_sample - std::round(subchips_per_sample)) < 1e-6)
    spdlog::warn(
        "{:g} Msps is a whole multiple of the 2.046 MHz BOC(1,1) subchip rate: expect Galileo code errors of metres "
        "(a front end at 4, 5 or 12 Msps avoids them)",
        fs / 1e6);
  s.acquisition.sample_rate_hz = s.tracking.sample_rate_hz = fs;
  s.acquisition.if_hz = s.tracking.if_hz = if_hz;
  return s;
}

bool same_data_set(const galileo::GalileoEphemeris& a, const galileo::GalileoEphemeris& b) {
  return a.iod_nav == b.iod_nav && a.week == b.week && a.orbit.toe_s == b.orbit.toe_s;
}

}  // namespace

GalileoChannelSet::GalileoChannelSet(GalileoReceiverSettings settings, double sample_rate_hz, double if_hz)
    : cfg_(checked(std::move(settings), sample_rate_hz, if_hz)),
      search_(std::make_unique<GalileoAcquisition>(cfg_.acquisition)),
      window_(static_cast<std::size_t>(search_->samples_needed())),
      last_search_s_(-std::numeric_limits<double>::infinity()) {}

GalileoChannelSet::~GalileoChannelSet() = default;

bool GalileoChannelSet::tracked(int svid) const {
  return std::any_of(channels_.begin(), channels_.end(), [&](const auto& ch) { return ch->svid() == svid; });
}

void GalileoChannelSet::keep(const SampleBlock& block) {
  if (!channel_free()) {
    window_.clear();
    return;
  }
  window_.append(block.samples.data(), block.samples.size(), block.first_sample_index);
}

std::vector<int> GalileoChannelSet::candidates(const std::optional<SkyViewPoint>& where) const {
  std::vector<int> out;
  const bool predicted = where && !assisted_.galileo_ephemerides.empty();
  for (int svid = 1; svid <= kGalileoMaxSvid; ++svid) {
    if (tracked(svid)) continue;
    const auto& searchable = cfg_.acquisition.prns;
    if (!searchable.empty() && std::find(searchable.begin(), searchable.end(), svid) == searchable.end()) continue;
    if (predicted) {
      const galileo::GalileoEphemeris* eph = ephemeris(svid, where->t);
      if (eph == nullptr) continue;
      const SatelliteState sat = galileo::satellite_state(*eph, galileo::gst_from_gps_time(where->t));
      if (look_angles(where->r_ecef_m, sat.r_ecef_m).elevation_rad < 0.0) continue;
    }
    out.push_back(svid);
  }
  return out;
}

void GalileoChannelSet::acquire_if_due(double t_s, const std::optional<SkyViewPoint>& where) {
  if (!channel_free() || !window_.full() || t_s - last_search_s_ < cfg_.reacquire_interval_s) return;
  last_search_s_ = t_s;
  const std::vector<int> svids = candidates(where);
  if (svids.empty()) return;
  const std::vector<Sample> samples = window_.in_order();
  std::vector<GalileoAcquisitionResult> found;
  for (const GalileoAcquisitionResult& r : search_->search(samples, svids))
    if (r.detected && !tracked(r.satellite.prn)) found.push_back(r);
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.cn0_dbhz > b.cn0_dbhz; });
  for (const GalileoAcquisitionResult& r : found) {
    if (!channel_free()) break;
    start_channel(r, window_.first_index());
  }
}

void GalileoChannelSet::start_channel(const GalileoAcquisitionResult& r, std::int64_t first_sample) {
  spdlog::debug("{} acquired: {:.1f} Hz, {:.2f} chips, {:.1f} dB-Hz", r.satellite.to_string(), r.doppler_hz,
                r.code_phase_chips, r.cn0_dbhz);
  if (std::find(acquired_.begin(), acquired_.end(), r.satellite.prn) == acquired_.end())
    acquired_.push_back(r.satellite.prn);
  E1ChannelStart start;
  start.satellite = r.satellite;
  start.doppler_hz = r.doppler_hz;
  start.code_phase_chips = r.code_phase_chips;
  start.sample_index = first_sample;
  channels_.push_back(std::make_unique<GalileoChannel>(
      cfg_.tracking, cfg_.loops, start, aiding_ ? aiding_->e1_controller_for(r.satellite.prn) : nullptr));
}

void GalileoChannelSet::collect_published(const std::optional<GpsTime>& t) {
  for (const auto& ch : channels_) ch->collect_published(t ? ephemeris(ch->svid(), *t) : nullptr, t.has_value());
}

void GalileoChannelSet::release_all() {
  for (const auto& ch : channels_) ch->end();
  channels_.clear();
  last_search_s_ = -std::numeric_limits<double>::infinity();
}

bool GalileoChannelSet::after_block() {
  bool fresh = false;
  for (const auto& ch : channels_) {
    const InavNavigation& nav = ch->decoder().navigation();
    if (const auto g = nav.ggto()) ggto_ = g;
    const auto eph = nav.ephemeris();
    if (!eph) continue;
    const auto known = decoded_.find(ch->svid());
    if (known != decoded_.end() && same_data_set(known->second, *eph)) continue;
    spdlog::info("{}: ephemeris IODnav {} decoded", ch->satellite().to_string(), eph->iod_nav);
    decoded_[ch->svid()] = *eph;
    fresh = true;
  }
  std::erase_if(channels_, [](const auto& ch) {
    if (ch->tracking().state() != E1ChannelState::lost) return false;
    spdlog::info("{}: loss of lock", ch->satellite().to_string());
    ch->end();
    return true;
  });
  return fresh;
}

void GalileoChannelSet::set_assisted(const NavData& nav) {
  assisted_ = NavData{};
  assisted_.galileo_ephemerides = nav.galileo_ephemerides;
  assisted_.source = nav.source;
}

const galileo::GalileoEphemeris* GalileoChannelSet::ephemeris(int svid, const GpsTime& t) const {
  if (const auto it = decoded_.find(svid); it != decoded_.end()) return &it->second;
  return select_galileo_ephemeris(assisted_, svid, galileo::gst_from_gps_time(t));
}

std::map<int, galileo::GalileoEphemeris> GalileoChannelSet::in_use(const GpsTime& t) const {
  std::map<int, galileo::GalileoEphemeris> out;
  for (const auto& ch : channels_)
    if (const galileo::GalileoEphemeris* e = ephemeris(ch->svid(), t)) out.emplace(ch->svid(), *e);
  return out;
}

std::optional<GalileoWeekMark> GalileoChannelSet::week_mark() const {
  for (const auto& ch : channels_) {
    const auto mark = ch->decoder().navigation().time_mark();
    if (mark && mark->week) return GalileoWeekMark{ch->svid(), *mark->week, mark->tow_s};
  }
  return std::nullopt;
}

}  // namespace deepnav
