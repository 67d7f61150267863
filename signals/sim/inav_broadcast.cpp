#include "signals/sim/inav_broadcast.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "signals/galileo/galileo_constants.hpp"
#include "signals/galileo/inav_page.hpp"
#include "signals/sim/floor_div.hpp"

namespace deepnav {
namespace {

namespace inav = galileo::inav;

constexpr std::int64_t kWeek_s = 604800;
constexpr std::int64_t kSubframe_s = 30;
constexpr std::int64_t kPeriodsPerSecond = 250;
/// What a page slot of the nominal E1-B subframe carries.
enum class Slot { ephemeris1, ephemeris2, ephemeris3, ephemeris4, iono_health, utc, almanac_7_9, almanac_8_10, spare };
constexpr Slot kSubframeSlots[15] = {Slot::ephemeris2,   Slot::ephemeris4, Slot::utc,        Slot::almanac_7_9,
                                     Slot::almanac_8_10, Slot::spare,      Slot::spare,      Slot::spare,
                                     Slot::spare,        Slot::spare,      Slot::ephemeris1, Slot::ephemeris3,
                                     Slot::iono_health,  Slot::spare,      Slot::spare};
constexpr int kSpareTimeValid = 2;  ///< word 0's time field: binary 10, week and TOW valid

/// The ephemeris with its angles in one turn, as the words' fields hold them.
galileo::GalileoEphemeris wrapped_angles(galileo::GalileoEphemeris eph) {
  for (double* angle : {&eph.orbit.m0_rad, &eph.orbit.omega0_rad, &eph.orbit.omega_rad, &eph.orbit.i0_rad})
    *angle = std::remainder(*angle, 2.0 * galileo::kPi);
  return eph;
}

inav::Word word5(const NavData& nav, const galileo::GalileoEphemeris& eph, int week, int tow) {
  inav::IonoDelayHealthWord w;
  w.iono = nav.galileo_iono;
  w.bgd_e1e5a_s = eph.bgd_e1e5a_s;
  w.bgd_e1e5b_s = eph.bgd_e1e5b_s;
  w.e5b = eph.e5b;
  w.e1b = eph.e1b;
  w.week = week % 4096;
  w.tow_s = tow;
  return inav::encode_iono_delay_health_word(w);
}

inav::Word word6(const NavData& nav, int tow) {
  inav::UtcWord w;
  w.utc = nav.galileo_utc;
  // GST-UTC shares the leap second fields with GPS-UTC (RINEX's one LEAP SECONDS line).
  w.utc.delta_t_ls = nav.utc.delta_t_ls;
  w.utc.delta_t_lsf = nav.leap_seconds_valid && (nav.utc.wn_lsf != 0 || nav.utc.delta_t_lsf != 0) ? nav.utc.delta_t_lsf
                                                                                                  : nav.utc.delta_t_ls;
  w.utc.wn_lsf = nav.utc.wn_lsf % 256;
  w.utc.dn = nav.utc.dn;
  w.utc.wnt = ((nav.galileo_utc.wnt % 256) + 256) % 256;
  w.tow_s = tow;
  return inav::encode_utc_word(w);
}

inav::Word word10(const NavData& nav) {
  inav::AlmanacBatch batch;
  batch.ggto = nav.ggto;
  batch.ggto.wn0g = ((nav.ggto.wn0g % 64) + 64) % 64;
  return inav::encode_almanac_word(10, batch);
}

}  // namespace

inav::Word synthesized_inav_word(const NavData& nav, const galileo::GalileoEphemeris& eph, std::int64_t page_start_s) {
  if (page_start_s % 2 != 0)
    throw std::logic_error(fmt::format("I/NAV page start at GST second {} is not even", page_start_s));
  const int week = static_cast<int>(floor_div(page_start_s, kWeek_s));
  const int tow = static_cast<int>(page_start_s - week * kWeek_s);
  const std::int64_t subframe = floor_div(page_start_s, kSubframe_s);
  const int slot = static_cast<int>((page_start_s - subframe * kSubframe_s) / 2);
  const bool odd_subframe = subframe % 2 != 0;
  switch (const Slot what = kSubframeSlots[slot]) {
    case Slot::ephemeris1:
    case Slot::ephemeris2:
    case Slot::ephemeris3:
    case Slot::ephemeris4:
      return inav::encode_ephemeris_word(1 + static_cast<int>(what) - static_cast<int>(Slot::ephemeris1),
                                         wrapped_angles(eph));
    case Slot::iono_health:
      return word5(nav, eph, week, tow);
    case Slot::utc:
      return word6(nav, tow);
    case Slot::almanac_8_10:
      // Word 10 for its GGTO; the almanac words themselves are not sent.
      return odd_subframe ? word10(nav) : inav::encode_dummy_word();
    case Slot::almanac_7_9:
      return inav::encode_dummy_word();
    case Slot::spare:
      break;
  }
  return inav::encode_spare_word(inav::SpareWord{kSpareTimeValid, week % 4096, tow});
}

InavSymbolTable::InavSymbolTable(const NavData& nav, const galileo::GalileoEphemeris& eph, std::int64_t first_period,
                                 std::int64_t last_period) {
  const std::int64_t first_page = floor_div(floor_div(first_period, kPeriodsPerSecond), 2);
  const std::int64_t last_page = floor_div(floor_div(last_period, kPeriodsPerSecond), 2);
  first_period_ = first_page * 2 * kPeriodsPerSecond;
  signs_.reserve(static_cast<std::size_t>((last_page - first_page + 1) * 2 * kPeriodsPerSecond));
  for (std::int64_t page = first_page; page <= last_page; ++page) {
    inav::NominalPage p;
    p.word = synthesized_inav_word(nav, eph, page * 2);
    for (const inav::PagePartTransmission& part : inav::encode_page(p)) {
      for (std::uint8_t symbol : part) signs_.push_back(symbol == 0 ? 1 : -1);
    }
  }
}

int InavSymbolTable::sign_at_period(std::int64_t period) const {
  const std::int64_t i = period - first_period_;
  if (i < 0 || i >= static_cast<std::int64_t>(signs_.size()))
    throw std::logic_error(fmt::format("I/NAV symbol of code period {} is outside the table", period));
  return signs_[static_cast<std::size_t>(i)];
}

}  // namespace deepnav
