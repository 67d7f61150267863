#pragma once
// The broadcast navigation data the receiver uses: each satellite's ephemeris, the
// ionosphere and the UTC parameters. What the satellites' own signals gave wins; until then,
// assistance (a navigation file) fills in, so that an assisted start needs only a transmit
// time, one subframe, rather than a whole frame per satellite.
#include <map>
#include <optional>
#include <set>

#include "ins/gps_time.hpp"
#include "receiver/navdata/nav_decoder.hpp"
#include "signals/ephemeris.hpp"
#include "signals/iono_utc.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

class BroadcastNavigation {
 public:
  /// Ephemerides to fall back on (replacing those an earlier call gave).
  void set_assisted(const NavData& nav) { assisted_ = nav; }
  /// Ionosphere parameters to use until the broadcast ones (subframe 4 page 18, sent once
  /// every 12.5 min) are decoded; ignored once they are.
  void set_assisted_iono(const IonoParameters& iono);

  /// The decoder of `prn`'s channel completed an ephemeris: it replaces the PRN's, and its
  /// ionosphere and UTC parameters, where decoded, replace the receiver's.
  void take_decoded(int prn, const NavDecoder& decoder);
  /// An ephemeris from elsewhere (the prediction a guided channel started from), for a PRN
  /// that has none.
  void adopt(int prn, const Ephemeris& ephemeris);
  /// Gives `prn` the assisted ephemeris valid at `t` when it has none yet.
  void adopt_assisted(int prn, const GpsTime& t);
  bool has_assistance() const { return assisted_.has_value(); }

  /// The ephemeris in use for a PRN, nullptr when there is none.
  const Ephemeris* ephemeris(int prn) const;
  /// The PRN's ephemeris in use, else the assisted one valid at `t`.
  std::optional<Ephemeris> available(int prn, const GpsTime& t) const;
  /// Every ephemeris in use (decoded, else assisted), by PRN.
  const std::map<int, Ephemeris>& in_use() const { return ephemerides_; }
  /// Only those decoded from the signal (what nav.rnx reports).
  std::map<int, Ephemeris> decoded() const;
  const IonoParameters& iono() const { return iono_; }
  const UtcParameters& utc() const { return utc_; }

 private:
  std::map<int, Ephemeris> ephemerides_;
  std::set<int> decoded_prns_;  ///< PRNs whose entry in ephemerides_ came from the signal
  IonoParameters iono_;
  UtcParameters utc_;
  std::optional<NavData> assisted_;
};

}  // namespace deepnav
