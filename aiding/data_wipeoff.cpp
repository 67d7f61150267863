#include "aiding/data_wipeoff.hpp"

#include <stdexcept>

#include "ins/gps_time.hpp"
#include "receiver/navdata/nav_decoder.hpp"

namespace deepnav::aiding {
namespace {

/// The monitor's expected bit error rate is taken this much below the estimated C/N0: the
/// ideal-loop rate understates a steered loop's (phase jitter, the estimate's own scatter),
/// and an understated rate turns into false alarms that make the data unknown.
constexpr double kErrorRateMargin_db = 1.0;
/// A bit judged without a wiped phase reference: possibly half a cycle off.
constexpr double kUnreferencedErrorRate = 0.4;

}  // namespace

void DataWipeoff::learn(const NavDecoder& decoder) {
  if (decoder.subframes_decoded() == subframes_learned_) return;
  subframes_learned_ = decoder.subframes_decoded();
  if (decoder.last_decoded()) predictor_.learn(*decoder.last_decoded());
}

void DataWipeoff::assist(const Ephemeris& eph) {
  if (assisted_iode_ == eph.iode) return;
  assisted_iode_ = eph.iode;
  try {
    predictor_.assist(eph);
  } catch (const std::invalid_argument&) {
    // A value LNAV cannot carry: the file's data cannot be what was broadcast; learn instead.
  }
}

std::optional<std::int64_t> DataWipeoff::bit_index(const NavDecoder& decoder, const Ephemeris& eph,
                                                   std::int64_t bit_start_period) {
  // The middle of the bit: an edge could round either way.
  const std::optional<double> sow = decoder.transmit_time_sow(bit_start_period + 10, 0.0);
  if (!sow) return std::nullopt;
  int week = eph.week;
  if (*sow - eph.toe_s > 0.5 * kSecondsPerWeek) --week;
  if (*sow - eph.toe_s < -0.5 * kSecondsPerWeek) ++week;
  return nav_bit_index(GpsTime::normalized(week, *sow));
}

int DataWipeoff::wipe_sign(std::int64_t bit, int polarity) const { return predictor_.sign(bit) * polarity; }

NavBitMonitor::Check DataWipeoff::observe(std::int64_t bit, const std::complex<double>& prompt,
                                          const std::optional<std::complex<double>>& phase_reference, int polarity,
                                          double cn0_dbhz) {
  const double projected = phase_reference ? (prompt * std::conj(*phase_reference)).real() : prompt.real();
  const int sign = projected == 0.0 || polarity == 0 ? 0 : (projected > 0.0 ? 1 : -1) * polarity;
  const double error_rate = phase_reference || predictor_.sign(bit) == 0
                                ? nav_bit_error_rate(cn0_dbhz - kErrorRateMargin_db)
                                : kUnreferencedErrorRate;
  return monitor_.observe(predictor_, bit, sign, error_rate);
}

}  // namespace deepnav::aiding
