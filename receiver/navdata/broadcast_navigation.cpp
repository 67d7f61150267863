#include "receiver/navdata/broadcast_navigation.hpp"

#include <spdlog/spdlog.h>

namespace deepnav {

void BroadcastNavigation::set_assisted_iono(const IonoParameters& iono) {
  if (!iono_.valid) iono_ = iono;
}

void BroadcastNavigation::take_decoded(int prn, const NavDecoder& decoder) {
  ephemerides_[prn] = *decoder.ephemeris();
  decoded_prns_.insert(prn);
  if (decoder.iono().valid) iono_ = decoder.iono();
  if (decoder.utc().valid) utc_ = decoder.utc();
  spdlog::debug("PRN {:2d}: ephemeris IODE {}", prn, decoder.ephemeris()->iode);
}

void BroadcastNavigation::adopt(int prn, const Ephemeris& ephemeris) { ephemerides_.emplace(prn, ephemeris); }

void BroadcastNavigation::adopt_assisted(int prn, const GpsTime& t) {
  if (!assisted_ || ephemerides_.count(prn)) return;
  if (const Ephemeris* e = assisted_->select(prn, t)) ephemerides_[prn] = *e;
}

const Ephemeris* BroadcastNavigation::ephemeris(int prn) const {
  const auto it = ephemerides_.find(prn);
  return it == ephemerides_.end() ? nullptr : &it->second;
}

std::optional<Ephemeris> BroadcastNavigation::available(int prn, const GpsTime& t) const {
  if (const Ephemeris* e = ephemeris(prn)) return *e;
  if (assisted_) {
    if (const Ephemeris* a = assisted_->select(prn, t)) return *a;
  }
  return std::nullopt;
}

std::map<int, Ephemeris> BroadcastNavigation::decoded() const {
  std::map<int, Ephemeris> out;
  for (int prn : decoded_prns_) out.emplace(prn, ephemerides_.at(prn));
  return out;
}

}  // namespace deepnav
