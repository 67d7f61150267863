#include "receiver/tracking/e1_correlator.hpp"

#include <cmath>
#include <stdexcept>

#include "receiver/tracking/kernels/e1_kernels.hpp"

namespace deepnav {

E1CorrelatorSums correlate_e1(const Sample* samples, int n, const E1CorrelatorSpan& span,
                              const E1CorrelatorCodes& codes) {
  if (!(span.code_step_chips > 0.0 && span.code_step_chips <= 1.0))
    throw std::invalid_argument("E1 correlator: code step must be in (0, 1] chip per sample (at least 1.023 Msps)");
  if (codes.pilot == nullptr || codes.data == nullptr || codes.noise == nullptr)
    throw std::invalid_argument("E1 correlator: pilot, data and noise codes are all required");
  if (n <= 0) return {};
  return e1_correlator_detail::correlate_portable(samples, n, span, codes);
}

double boc11_level(const galileo::E1CodeChips& code, double chip_phase) {
  const double f = std::floor(chip_phase);
  const double sc = chip_phase - f < 0.5 ? 1.0 : -1.0;
  const auto length = static_cast<double>(galileo::kE1CodeLength_chips);
  const double index = f - length * std::floor(f / length);
  return sc * code[static_cast<std::size_t>(index)];
}

}  // namespace deepnav
