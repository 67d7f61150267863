#include "receiver/tracking/e1_correlator.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>

#include "receiver/tracking/padded_correlation.hpp"

namespace deepnav {
namespace {

using namespace correlator_detail;

constexpr int kLength = galileo::kE1CodeLength_chips;
using HalfChipTable = PaddedCodeTable<2 * kLength>;

/// The BOC(1,1) replica of a code as half-chips: entry 2k is chip k, entry 2k + 1 its negative
/// (the subcarrier is +1 in a chip's first half).
const HalfChipTable& half_chip_table(const galileo::E1CodeChips& code) {
  return cached_code_table<galileo::E1CodeChips, HalfChipTable>(code, [](const galileo::E1CodeChips& chips) {
    return std::make_unique<HalfChipTable>([&chips](int e) {
      const std::int8_t c = chips[static_cast<std::size_t>(e / 2)];
      return e % 2 == 0 ? c : static_cast<std::int8_t>(-c);
    });
  });
}

void validate(const E1CorrelatorSpan& span, const E1CorrelatorCodes& codes) {
  if (!(span.code_step_chips > 0.0 && span.code_step_chips <= 1.0))
    throw std::invalid_argument("E1 correlator: code step must be in (0, 1] chip per sample (at least 1.023 Msps)");
  if (codes.pilot == nullptr || codes.data == nullptr || codes.noise == nullptr)
    throw std::invalid_argument("E1 correlator: pilot, data and noise codes are all required");
}

/// The span in half-chips, the C/A correlator's span type.
CorrelatorSpan half_chip_span(const E1CorrelatorSpan& s) {
  CorrelatorSpan h;
  h.carrier_phase_cycles = s.carrier_phase_cycles;
  h.carrier_step_cycles = s.carrier_step_cycles;
  h.code_phase_chips = 2.0 * s.code_phase_chips;
  h.code_step_chips = 2.0 * s.code_step_chips;
  h.spacing_chips = 2.0 * s.spacing_chips;
  h.very_spacing_chips = 2.0 * s.very_spacing_chips;
  h.magnitude_bits = s.magnitude_bits;
  return h;
}

}  // namespace

E1CorrelatorSums correlate_e1(const CorrelatorInput& input, int n, const E1CorrelatorSpan& span,
                              const E1CorrelatorCodes& codes) {
  return correlate_e1(best_correlator_kernel(), input, n, span, codes);
}

E1CorrelatorSums correlate_e1(CorrelatorKernel kernel, const CorrelatorInput& input, int n,
                              const E1CorrelatorSpan& span, const E1CorrelatorCodes& codes) {
  validate(span, codes);
  if (n <= 0) return {};
  CorrelatorSpan h = half_chip_span(span);
  if (h.magnitude_bits < 0) h.magnitude_bits = sample_magnitude_bits(input.samples, n);
  // Pass 1: pilot at five delays, the data code at the prompt in the noise slot.
  h.noise_tap = true;
  const CorrelatorSums pilot =
      correlate_padded(kernel, input, n, h, half_chip_table(*codes.pilot).view(), half_chip_table(*codes.data).view());
  E1CorrelatorSums out;
  out.very_early = pilot.very_early;
  out.early = pilot.early;
  out.prompt = pilot.prompt;
  out.late = pilot.late;
  out.very_late = pilot.very_late;
  out.data_prompt = pilot.noise;
  if (span.noise_tap) {  // pass 2: the untracked PRN's pilot at the prompt
    h.noise_tap = false;
    h.very_spacing_chips = 0.0;
    const HalfChipTable& noise = half_chip_table(*codes.noise);
    out.noise = correlate_padded(kernel, input, n, h, noise.view(), noise.view()).prompt;
  }
  return out;
}

double boc11_level(const galileo::E1CodeChips& code, double chip_phase) {
  const double f = std::floor(chip_phase);
  const double sc = chip_phase - f < 0.5 ? 1.0 : -1.0;
  const auto length = static_cast<double>(kLength);
  const double index = f - length * std::floor(f / length);
  return sc * code[static_cast<std::size_t>(index)];
}

E1CorrelatorSums correlate_e1_reference(const Sample* samples, int n, const E1CorrelatorSpan& s,
                                        const E1CorrelatorCodes& codes) {
  validate(s, codes);
  E1CorrelatorSums out;
  const bool very = s.very_spacing_chips > 0.0;
  const double half = 0.5 * s.spacing_chips, very_half = 0.5 * s.very_spacing_chips;
  for (int k = 0; k < n; ++k) {
    const double phase = s.carrier_phase_cycles + k * s.carrier_step_cycles;
    const std::complex<double> x(samples[k].real(), samples[k].imag());
    const std::complex<double> v = x * std::polar(1.0, -2.0 * M_PI * (phase - std::floor(phase)));
    const double chip = s.code_phase_chips + k * s.code_step_chips;
    out.early += v * boc11_level(*codes.pilot, chip + half);
    out.prompt += v * boc11_level(*codes.pilot, chip);
    out.late += v * boc11_level(*codes.pilot, chip - half);
    if (very) {
      out.very_early += v * boc11_level(*codes.pilot, chip + very_half);
      out.very_late += v * boc11_level(*codes.pilot, chip - very_half);
    }
    out.data_prompt += v * boc11_level(*codes.data, chip);
    if (s.noise_tap) out.noise += v * boc11_level(*codes.noise, chip);
  }
  return out;
}

}  // namespace deepnav
