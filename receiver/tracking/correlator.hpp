#pragma once
// The receiver's hot path: carrier and code wipe-off of a span of samples against
// early, prompt, late (optionally very-early/very-late) and noise replicas, with
// constant code rate and carrier frequency over the span.
//
// Numerics (fixed point, identical integers in every kernel, so the SIMD kernels are
// bit-exact with the portable one; correlate_reference() is the double-precision truth):
// - The span is cut into runs of 4096 samples; each run restarts the carrier and code
//   accumulators from the exact double-precision phases, so nothing drifts.
// - Carrier: a 21-bit phase accumulator per sample (step error below 2^-22 cycle per
//   sample, at most 0.35 degree at the end of a run) whose top 5 bits index an int16
//   cos/sin table with bins centred on (p + 1/2) * 2 pi / 32: phase error within
//   +-5.6 degrees, averaging out as the phase moves through the bins (mean amplitude loss
//   0.16 %, 0.014 dB); a replica phase that repeats exactly (IF = fs/4 without Doppler)
//   can keep up to that error in its sums.
// - Wipe-off. The span's largest |I| or |Q|, below 2^b, picks the scaling: for b <= 7
//   (|I|, |Q| <= 127: 1- to 8-bit converters) the table has amplitude 127 (every entry
//   fits int8, |c|, |s| <= 126) and the products are exact (|I c + Q s| <= 32004); larger
//   inputs, up to full-scale int16, have their products rounded to 15 fraction bits
//   (pmulhrsw) at table amplitude 23000. No int16 value can overflow for any input. The
//   int8 table's rounding moves an entry by at most 0.2 degree and 0.4 % in amplitude;
//   with the binning its mean amplitude loss is 0.11 % (0.010 dB; the amplitude-23000
//   table's 0.16 %).
// - Code: the prompt position is a 27-fraction-bit chip count (error below 1.6e-5 chip
//   at the end of a run); the other taps sit at offsets rounded to 2^-11 chip (error at
//   most 2.4e-4 chip, equal and opposite for early and late, so the early-late
//   discriminator has no bias). Chips come from a table window permuted in registers.
// - Sums: int16 x +-1 multiply-accumulate into int32 lanes (AVX-512: vpdpwssd), moved to
//   int64 at the end of every run (AVX2: every 1024 samples), long before any lane could
//   overflow; the result is the int64 sum times the table's scale.
// - Kernels, one file each under receiver/tracking/kernels/, compiled with their own instruction
//   set flags: portable (the definition), AVX2 (for b <= 7 an int8 pipeline: the samples
//   packed to bytes, the carrier replica built as bytes, vpmaddubsw pair products with the
//   samples' signs moved onto the replica; larger inputs in int16), AVX-512 (BW + VNNI) and
//   NEON (AArch64). All give the same integers.
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include "receiver/sources/sample_source.hpp"
#include "signals/ca_code.hpp"

namespace deepnav {

struct CorrelatorSums {
  std::complex<double> early, prompt, late;    ///< at +spacing/2, 0, -spacing/2 chips from the prompt
  std::complex<double> very_early, very_late;  ///< at +-very_spacing/2 chips; zero when disabled
  std::complex<double> noise;                  ///< prompt timing on an untracked PRN's code: noise reference
};

struct CorrelatorSpan {
  double carrier_phase_cycles = 0.0;  ///< phase of the replica at the first sample (IF + Doppler)
  double carrier_step_cycles = 0.0;   ///< per sample
  double code_phase_chips = 0.0;      ///< prompt code phase at the first sample (any value; taken modulo 1023)
  double code_step_chips = 0.0;       ///< per sample, in (0, 2]
  double spacing_chips = 0.5;         ///< early-late spacing
  double very_spacing_chips = 0.0;    ///< very-early/very-late spacing; 0 disables them
  /// Bits of the largest |I| or |Q| in the span (sample_magnitude_bits()), or of a larger
  /// set of samples holding the span (one scan of a block serves all its channels); it
  /// picks the fixed-point scaling and must not be below the span's own. -1: scanned here.
  int magnitude_bits = -1;
  /// Whether the noise tap runs; without it CorrelatorSums::noise is zero (a tracking channel
  /// needs the noise reference only now and then: the C/N0 estimate averages it over seconds).
  bool noise_tap = true;
};

/// Instruction-set variants of the kernel; correlate() picks the best one the CPU supports.
/// avx512 needs AVX-512BW and VNNI; neon is AArch64's Advanced SIMD. The SIMD kernels take
/// their chips from a 16 or 32 chip window per block of samples: with every tap within 1 chip
/// of the prompt that holds for code steps up to 13/15 chip per sample (sample rates above
/// 1.18 Msps); other spans go to the portable kernel, which gives the same integers.
enum class CorrelatorKernel { portable, avx2, avx512, neon };
/// The kernel correlate() uses without an explicit one: the fastest this CPU can run, unless
/// the environment variable DEEPNAV_CORRELATOR_KERNEL (portable, avx2, avx512, neon) or
/// use_correlator_kernel() chose another (to measure a CPU without the wider instructions:
/// DEEPNAV_CORRELATOR_KERNEL=avx2). A named kernel the CPU cannot run throws
/// std::invalid_argument.
CorrelatorKernel best_correlator_kernel();
/// The fastest kernel this CPU can run, whatever was chosen.
CorrelatorKernel fastest_correlator_kernel();
/// Makes `kernel` the one correlate() uses from now on, in every thread (call it before
/// processing starts). Throws std::invalid_argument if the CPU cannot run it.
void use_correlator_kernel(CorrelatorKernel kernel);
/// The kernels this CPU can run (portable always), slowest first, for tests and benchmarks.
std::vector<CorrelatorKernel> available_correlator_kernels();
/// "portable", "avx2", "avx512", "neon".
const char* correlator_kernel_name(CorrelatorKernel kernel);
/// The kernel of a name; throws std::invalid_argument for an unknown name or one this CPU
/// cannot run.
CorrelatorKernel correlator_kernel_named(const std::string& name);

/// The samples of a span: interleaved I/Q, and optionally the same samples as planar I and Q
/// arrays (deinterleave()), which the AVX-512 kernel reads without deinterleaving them
/// itself: the channels sharing a block then share one deinterleaving pass.
struct CorrelatorInput {
  const Sample* samples = nullptr;
  const std::int16_t* i = nullptr;  ///< i[k] == samples[k].real(), or nullptr
  const std::int16_t* q = nullptr;  ///< q[k] == samples[k].imag(), or nullptr
};
/// Whether the kernel correlate() picks reads CorrelatorInput::i/q (else they are ignored).
bool correlator_reads_planar_input();
/// i[k] = x[k].real(), q[k] = x[k].imag() for k in [0, n).
void deinterleave(const Sample* x, int n, std::int16_t* i, std::int16_t* q);

/// Fills block.magnitude_bits, and block.planar where the kernel reads it.
void prepare_for_correlation(SampleBlock& block);

/// Bits of the largest |I| or |Q| of n samples: every one within +-(2^b - 1); -32768 gives 16.
int sample_magnitude_bits(const Sample* samples, int n);

/// Correlator sums over n samples. `noise_code` is the code of a PRN that is not tracked.
/// Sums are in sample units: a noise-free signal of amplitude A aligned with the prompt
/// gives |prompt| = A n. Throws std::invalid_argument for a code step outside (0, 2].
CorrelatorSums correlate(const Sample* samples, int n, const CorrelatorSpan& span, const CaCodeChips& code,
                         const CaCodeChips& noise_code);
/// The same with an explicit kernel (must be one of available_correlator_kernels()).
CorrelatorSums correlate(CorrelatorKernel kernel, const Sample* samples, int n, const CorrelatorSpan& span,
                         const CaCodeChips& code, const CaCodeChips& noise_code);
/// The same on a CorrelatorInput (every kernel gives the same integers with or without the planar copy).
CorrelatorSums correlate(const CorrelatorInput& input, int n, const CorrelatorSpan& span, const CaCodeChips& code,
                         const CaCodeChips& noise_code);
CorrelatorSums correlate(CorrelatorKernel kernel, const CorrelatorInput& input, int n, const CorrelatorSpan& span,
                         const CaCodeChips& code, const CaCodeChips& noise_code);

/// The same sums computed sample by sample in double precision, without any of the
/// shortcuts above: the reference the fast path is tested against.
CorrelatorSums correlate_reference(const Sample* samples, int n, const CorrelatorSpan& span, const CaCodeChips& code,
                                   const CaCodeChips& noise_code);

}  // namespace deepnav
