#include <algorithm>
#include <cmath>
#include <complex>

#include "receiver/tracking/kernels/e1_kernels.hpp"

namespace deepnav::e1_correlator_detail {
namespace {

constexpr int kRun = 1024;  // samples between exact restarts of the carrier phasor
constexpr int kLength = galileo::kE1CodeLength_chips;

/// Code position of a tap: whole chip in [0, 4092) and the fraction of it, advanced by carries
/// rather than floor() per sample; the BOC(1,1) subcarrier is +1 in a chip's first half.
struct TapCursor {
  int chip = 0;
  double fraction = 0.0;
  void set(double chips) {
    double w = std::fmod(chips, static_cast<double>(kLength));
    if (w < 0.0) w += kLength;
    const double f = std::floor(w);
    chip = static_cast<int>(f) % kLength;
    fraction = w - f;
  }
  double level(const galileo::E1CodeChips& code) const {
    const double c = code[static_cast<std::size_t>(chip)];
    return fraction < 0.5 ? c : -c;
  }
  void advance(double step) {
    fraction += step;
    if (fraction >= 1.0) {  // steps are at most one chip
      fraction -= 1.0;
      if (++chip == kLength) chip = 0;
    }
  }
};

}  // namespace

E1CorrelatorSums correlate_portable(const Sample* x, int n, const E1CorrelatorSpan& s, const E1CorrelatorCodes& c) {
  const bool very = s.very_spacing_chips > 0.0;
  const double offsets[5] = {0.5 * s.very_spacing_chips, 0.5 * s.spacing_chips, 0.0, -0.5 * s.spacing_chips,
                             -0.5 * s.very_spacing_chips};
  std::complex<double> acc[5], data, noise;
  const std::complex<double> rotation = std::polar(1.0, -2.0 * M_PI * s.carrier_step_cycles);
  for (int first = 0; first < n; first += kRun) {
    const int end = std::min(n, first + kRun);
    const double phase0 = s.carrier_phase_cycles + first * s.carrier_step_cycles;
    std::complex<double> wipe = std::polar(1.0, -2.0 * M_PI * (phase0 - std::floor(phase0)));
    const double code0 = s.code_phase_chips + first * s.code_step_chips;
    TapCursor tap[5];
    for (int t = 0; t < 5; ++t) tap[t].set(code0 + offsets[t]);
    for (int k = first; k < end; ++k) {
      const std::complex<double> v = std::complex<double>(x[k].real(), x[k].imag()) * wipe;
      wipe *= rotation;
      for (int t = 1; t < 4; ++t) acc[t] += v * tap[t].level(*c.pilot);
      if (very) {
        acc[0] += v * tap[0].level(*c.pilot);
        acc[4] += v * tap[4].level(*c.pilot);
      }
      data += v * tap[2].level(*c.data);
      if (s.noise_tap) noise += v * tap[2].level(*c.noise);
      for (TapCursor& t : tap) t.advance(s.code_step_chips);
    }
  }
  E1CorrelatorSums out;
  out.very_early = acc[0];
  out.early = acc[1];
  out.prompt = acc[2];
  out.late = acc[3];
  out.very_late = acc[4];
  out.data_prompt = data;
  out.noise = noise;
  return out;
}

}  // namespace deepnav::e1_correlator_detail
