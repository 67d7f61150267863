#include "signals/sim/lnav_broadcast.hpp"

#include <stdexcept>

namespace deepnav {

lnav::LnavContent synthesized_lnav_content(const NavData& nav, const Ephemeris& eph) {
  lnav::LnavContent content;
  content.iono = nav.iono;
  content.utc = nav.utc;
  for (const auto& e : nav.ephemerides) {
    if (e.prn >= 1 && e.prn <= 32 && !content.almanac[e.prn - 1]) {
      content.almanac[e.prn - 1] = lnav::almanac_from_ephemeris(e);
    }
  }
  content.eph = eph;
  return content;
}

LnavSignTable::LnavSignTable(const lnav::LnavContent& content, std::int64_t first_ms, std::int64_t last_ms) {
  first_subframe_ = first_ms / 6000;
  const std::int64_t last_subframe = last_ms / 6000;
  signs_.reserve(static_cast<std::size_t>((last_subframe - first_subframe_ + 1) * lnav::kBitsPerSubframe));
  // Subframe 1 carries the week it is sent in (not toe's): its week number rolls over with
  // the time of week, in the first subframe 1 after a week boundary.
  lnav::LnavContent sent = content;
  for (std::int64_t g = first_subframe_; g <= last_subframe; ++g) {
    sent.transmission_week = static_cast<int>(g / lnav::kTowCountsPerWeek);
    const lnav::Subframe sf = lnav::subframe_of_week(sent, g % lnav::kTowCountsPerWeek);
    for (int i = 0; i < lnav::kBitsPerSubframe; ++i) signs_.push_back(lnav::subframe_bit(sf, i) ? -1 : 1);
  }
}

int LnavSignTable::sign_at_ms(std::int64_t ms) const { return sign_of_bit(ms / 20); }

int LnavSignTable::sign_of_bit(std::int64_t bit) const {
  const std::int64_t i = bit - first_subframe_ * lnav::kBitsPerSubframe;
  if (i < 0 || i >= static_cast<std::int64_t>(signs_.size())) {
    throw std::logic_error("LNAV bit outside the precomputed span");
  }
  return signs_[static_cast<std::size_t>(i)];
}

}  // namespace deepnav
