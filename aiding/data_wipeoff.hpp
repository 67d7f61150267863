#pragma once
// Data wipe-off for one steered channel: which sign each of its 20 ms bits carries before
// the bit is integrated, so that bits can be summed coherently across their edges.
//
// Holds the satellite's NavBitPredictor (learning every subframe the channel's NavDecoder
// decodes) and a NavBitMonitor that checks each received bit against the prediction: a
// failed prediction (a new upload, a page the predictor has not seen as it now reads) is
// found within a few bits and forgotten, and those bits are then integrated bit by bit
// again (the caller falls back to non-coherent combination) until the data are learned.
//
// Bit timing comes from the decoder's subframe anchor (code period -> transmit time), which
// stays valid however weak the signal gets, and the week from the ephemeris.
#include <complex>
#include <cstdint>
#include <optional>

#include "receiver/navdata/nav_bit_monitor.hpp"
#include "receiver/navdata/nav_bit_predictor.hpp"
#include "signals/ephemeris.hpp"

namespace deepnav {
class NavDecoder;
}

namespace deepnav::aiding {

class DataWipeoff {
 public:
  /// Learns the subframes `decoder` decoded since the last call.
  void learn(const NavDecoder& decoder);
  /// Assisted bits: subframes 1-3 encoded from a navigation file's ephemeris where the
  /// broadcast ones are not known, once per data set (IODE): a prediction the monitor finds
  /// failed is then learned from the signal, not assisted again. Only as good as the file's
  /// reproduction of the broadcast (NavBitPredictor::assist).
  void assist(const Ephemeris& eph);
  /// Absolute data bit (nav_bit_index) of the bit that starts at the channel's code period
  /// `bit_start_period`; nullopt before the decoder's first subframe.
  static std::optional<std::int64_t> bit_index(const NavDecoder& decoder, const Ephemeris& eph,
                                               std::int64_t bit_start_period);
  /// What to multiply the bit's prompt sum by to remove its data: +-1, or 0 when the bit
  /// is not predicted (or the decoder's polarity is not known).
  int wipe_sign(std::int64_t bit, int polarity) const;
  /// The bit as received against the prediction: the sign of its prompt projected on
  /// `phase_reference` (the wiped carrier phase around it), `polarity` applied; `cn0_dbhz`
  /// sets the error rate the test expects. Without a reference the in-phase sign is taken
  /// (the Costas loop's phase: right for learning words, but possibly half a cycle off
  /// after a stretch of unpredicted bits), and the test gives it the weight of a bit that is
  /// wrong 40 % of the time, so a slip there cannot condemn a correct prediction.
  NavBitMonitor::Check observe(std::int64_t bit, const std::complex<double>& prompt,
                               const std::optional<std::complex<double>>& phase_reference, int polarity,
                               double cn0_dbhz);

  const NavBitPredictor& predictor() const { return predictor_; }
  const NavBitMonitor& monitor() const { return monitor_; }

 private:
  NavBitPredictor predictor_;
  NavBitMonitor monitor_;
  int subframes_learned_ = 0;
  std::optional<int> assisted_iode_;
};

}  // namespace deepnav::aiding
