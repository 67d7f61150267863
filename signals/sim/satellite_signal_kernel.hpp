#pragma once
// The synthesizer's hot loop: adds one satellite's C/A or E1 signal to a block of samples.
// Within a segment code rate and carrier frequency are constant (the caller
// recomputes them from exact geometry every millisecond), so the code index is a
// fixed-point accumulator and the carrier a phasor rotated by a constant step.
#include <cstdint>

#include "signals/ca_code.hpp"

namespace deepnav {

struct SignalSegment {
  double carrier_phase_cycles = 0.0;  ///< phase of the first sample
  double carrier_step_cycles = 0.0;   ///< phase advance per sample (IF + Doppler) / fs
  double code_phase_chips = 0.0;      ///< code phase of the first sample, in [0, 1023)
  double code_step_chips = 0.0;       ///< code advance per sample (code rate / fs)
  float amplitude = 0.0f;             ///< sqrt(C) times the data bit (+1/-1)
};

/// i_out[k] += a c(k) cos(2 pi phi(k)), q_out[k] += a c(k) sin(2 pi phi(k)) for k in [0, n).
/// `scratch` must hold n floats. The code index wraps modulo 1023.
void add_satellite_segment(float* i_out, float* q_out, int n, const SignalSegment& segment, const CaCodeChips& code,
                           float* scratch);

/// Sub-chips per chip of a Galileo E1 waveform table: BOC(6,1) has 12 half cycles per chip,
/// so the CBOC waveform is constant on each twelfth of a chip and a table of twelfths,
/// read at the sample's sub-chip, samples it exactly.
inline constexpr int kE1SubchipsPerChip = 12;

/// The same for a Galileo E1 signal: the code phase counts chips of the 4092-chip code
/// period (segment.code_phase_chips in [0, 4092)) and `waveform` holds its 4092 * 12 levels
/// (the composite E1-B/E1-C waveform of the period's data symbol and secondary code chip).
/// segment.amplitude multiplies every level.
void add_e1_segment(float* i_out, float* q_out, int n, const SignalSegment& segment, const float* waveform,
                    float* scratch);

}  // namespace deepnav
