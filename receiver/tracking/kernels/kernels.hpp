#pragma once
// The correlator's kernels, one file per instruction set (each compiled with its own flags,
// see receiver/CMakeLists.txt), and what they share. Internal to the correlator: callers use
// receiver/tracking/correlator.hpp. The fixed-point numerics every kernel follows are described there.
//
// A kernel file compiled with wider instruction-set flags than the rest of the program must
// not emit any function the linker could share with other files (an inline std:: template
// instantiated there could be picked for a caller on a CPU without those instructions): the
// kernel files keep everything in anonymous namespaces, use only this header's plain types
// and intrinsics, and export one non-inline entry point per kernel.
#include <complex>
#include <cstdint>

namespace deepnav {
using Sample = std::complex<std::int16_t>;  // as in receiver/sources/sample_source.hpp (kept out of the kernel files)
}  // namespace deepnav

namespace deepnav::correlator_detail {

constexpr int kRun = 4096;         // samples per run: phases restart exactly at each run
constexpr int kCarrierBits = 21;   // carrier phase accumulator: 1 cycle = 2^21
constexpr int kCodeFracBits = 27;  // code position: chips with 27 fraction bits
constexpr int kTapFracBits = 11;   // tap offsets: chips with 11 fraction bits
constexpr int kPad = 64;           // code table entries before 0 and after period - 1 (window loads, tap offsets)
constexpr int kTaps = 6;           // early, prompt, late, very early, very late, noise
constexpr int kNoise = 5;
constexpr int kSmallBits = 7;  // |I|, |Q| <= 127: int8 carrier table, exact products (see the header)

/// Everything a kernel needs that does not change within a call.
struct Setup {
  const std::int16_t* cos_tab;  // 32 entries
  const std::int16_t* sin_tab;
  // Code levels, index = table entry (a chip, or a BOC half-chip), valid for -kPad .. period - 1 + kPad.
  const std::int16_t* code16;
  const std::int16_t* noise16;
  const std::int8_t* code8;
  const std::int8_t* noise8;
  int taps;           // 3 (E/P/L) or 5 (with VE/VL)
  bool noise;         // the noise tap runs (else its sums stay 0)
  int period;         // table entries per code period (1023 for C/A, 8184 for E1 BOC(1,1) half-chips)
  int h;              // whole entries the widest tap reaches beyond the prompt (>= 1)
  std::int16_t d[5];  // tap offsets in 2^-11 chip: E, P (0), L, VE, VL
};

/// Phases at the first sample of a run.
struct Run {
  std::uint32_t phi0, dphi;  // carrier, 2^21 per cycle (bits above 20 are ignored)
  std::int64_t pos0;         // prompt position in [0, wrap)
  std::int64_t inc;          // code step, 2^27 per entry
  std::int64_t wrap;         // period * 2^27
};

using Acc = std::int64_t[kTaps][2];

/// A run's samples: interleaved, and planar I and Q when the caller prepared them.
struct Input {
  const Sample* x;
  const std::int16_t* i;  // nullptr: deinterleave here
  const std::int16_t* q;
  Input at(int k) const { return {x + k, i ? i + k : nullptr, q ? q + k : nullptr}; }
};

/// Adds one run (at most kRun samples) to acc.
using KernelFn = void (*)(const Input&, int, const Run&, const Setup&, Acc&);

/// The integers every kernel must give: sample by sample (any span, any tap reach).
KernelFn portable_kernel(bool small);
int sample_bits_portable(const Sample* x, int n);

#if defined(__x86_64__)
/// x86 kernels. Only for spans whose taps fit the kernel's chip window (see correlate()).
KernelFn avx2_kernel(int taps, bool small, bool noise);
int sample_bits_avx2(const Sample* x, int n);
KernelFn avx512_kernel(int taps, bool small, bool planar, bool noise);
int sample_bits_avx512(const Sample* x, int n);
/// Deinterleaves whole groups of 32 samples; returns how many samples it did.
int deinterleave_avx512(const Sample* x, int n, std::int16_t* i, std::int16_t* q);
#endif

#if defined(__aarch64__)
KernelFn neon_kernel(int taps, bool small, bool noise);
int sample_bits_neon(const Sample* x, int n);
#endif

}  // namespace deepnav::correlator_detail
