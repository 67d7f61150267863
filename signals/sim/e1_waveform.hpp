#pragma once
// One Galileo satellite's E1 OS signal over a 4 ms code period on twelfths of a chip (the
// CBOC waveform is constant on each): the levels the signal kernel reads for each sample.
#include <vector>

namespace deepnav {

/// The composite E1 signal (ICD 2.3.3, galileo::e1_composite) of a PRN for a code period,
/// for the two cases of the E1-B data symbol d and the E1-C secondary code chip s: `same`
/// for d = s = +1 and `opposite` for d = +1, s = -1. The other two cases are their negatives:
/// the level of sub-chip j is d * (d == s ? same[j] : opposite[j]).
struct E1WaveformTables {
  std::vector<float> same, opposite;  ///< 4092 * 12 levels each, chip c's at 12 c .. 12 c + 11

  explicit E1WaveformTables(int prn);
  const float* levels(int data_sign, int secondary_sign) const {
    return data_sign == secondary_sign ? same.data() : opposite.data();
  }
};

}  // namespace deepnav
