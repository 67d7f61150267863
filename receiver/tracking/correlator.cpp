#include "receiver/tracking/correlator.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "receiver/tracking/kernels/kernels.hpp"
#include "receiver/tracking/padded_correlation.hpp"

namespace deepnav {
namespace {

using namespace correlator_detail;

constexpr double kCarrierOne = 2097152.0;  // 2^21
constexpr double kCodeOne = 134217728.0;   // 2^27
constexpr double kPeriodChips = 1023.0;

// ---------------------------------------------------------------------------------------
// Tables.

/// Carrier tables for one amplitude: cos/sin at (p + 1/2) * 2 pi / 32, built from one
/// quarter wave so that every entry has an exact mirror (sin(p) = cos(p - 8), cos(p + 16) =
/// -cos(p): the AVX2 kernels look up part of the table and apply the signs themselves).
struct CarrierTable {
  std::array<std::int16_t, 8> quarter;
  std::array<std::int16_t, 32> cos_tab, sin_tab;
  double scale;  // sums in sample units = integer sums * scale
};

CarrierTable make_carrier_table(double amplitude, double scale) {
  CarrierTable t{};
  for (int r = 0; r < 8; ++r)
    t.quarter[static_cast<std::size_t>(r)] =
        static_cast<std::int16_t>(std::lround(amplitude * std::cos((r + 0.5) * M_PI / 16.0)));
  for (int p = 0; p < 32; ++p) {
    const int q = p >> 3, r = p & 7;
    const std::int16_t m = t.quarter[static_cast<std::size_t>(r)], mm = t.quarter[static_cast<std::size_t>(7 - r)];
    const std::int16_t c[4] = {m, static_cast<std::int16_t>(-mm), static_cast<std::int16_t>(-m), mm};
    const std::int16_t s[4] = {mm, m, static_cast<std::int16_t>(-mm), static_cast<std::int16_t>(-m)};
    t.cos_tab[static_cast<std::size_t>(p)] = c[q];
    t.sin_tab[static_cast<std::size_t>(p)] = s[q];
  }
  t.scale = scale;
  return t;
}

/// Index 0: inputs of at most 7 bits (|I|, |Q| <= 127), amplitude 127, so that every entry
/// fits int8 (|c|, |s| <= 126) and |I c + Q s| <= 2 * 127 * 126 < 2^15: exact products.
/// Index 1: larger inputs, products rounded by 2^15, amplitude 23000 (the two rounded
/// products add to at most sqrt(2) 23000 + 1 < 2^15).
const CarrierTable& carrier_table(int bits) {
  static const std::array<CarrierTable, 2> tables = {make_carrier_table(127.0, 1.0 / 127.0),
                                                     make_carrier_table(23000.0, 32768.0 / 23000.0)};
  return tables[bits <= kSmallBits ? 0 : 1];
}

using CaTable = PaddedCodeTable<1023>;

/// The table of a C/A code. A receiver interleaves its channels over the same block, so each
/// thread keeps the tables of ca_code_chips()'s 32 constant codes, and of the last 64 other
/// codes it saw (cached_code_table()).
const CaTable& table_for(const CaCodeChips& code) {
  static const CaCodeChips* const kFirst = &ca_code_chips(1);
  static const CaCodeChips* const kLast = &ca_code_chips(32);
  const auto make = [](const CaCodeChips& chips) {
    return std::make_unique<CaTable>([&chips](int e) { return chips[static_cast<std::size_t>(e)]; });
  };
  if (std::less_equal<>()(kFirst, &code) && std::less_equal<>()(&code, kLast)) {
    // One of the 32 constant codes: its own slot, no search and no comparison.
    thread_local std::array<std::unique_ptr<CaTable>, 32> constant_tables;
    auto& table = constant_tables[static_cast<std::size_t>(&code - kFirst)];
    if (!table) table = make(code);
    return *table;
  }
  return cached_code_table<CaCodeChips, CaTable>(code, make);
}

KernelFn pick_kernel(CorrelatorKernel kernel, int taps, bool small, [[maybe_unused]] bool planar,
                     [[maybe_unused]] bool noise) {
  switch (kernel) {
#if defined(__x86_64__)
    case CorrelatorKernel::avx512:
      return avx512_kernel(taps, small, planar, noise);
    case CorrelatorKernel::avx2:
      return avx2_kernel(taps, small, noise);
#endif
#if defined(__aarch64__)
    case CorrelatorKernel::neon:
      return neon_kernel(taps, small, noise);
#endif
    default:
      return portable_kernel(small);
  }
}

int sample_bits(CorrelatorKernel kernel, const Sample* x, int n) {
  switch (kernel) {
#if defined(__x86_64__)
    case CorrelatorKernel::avx512:
      return sample_bits_avx512(x, n);
    case CorrelatorKernel::avx2:
      return sample_bits_avx2(x, n);
#endif
#if defined(__aarch64__)
    case CorrelatorKernel::neon:
      return sample_bits_neon(x, n);
#endif
    default:
      return sample_bits_portable(x, n);
  }
}

/// Window width (chips) of a SIMD kernel's code lookup and samples per block.
struct Geometry {
  int window, block;
};
Geometry geometry(CorrelatorKernel kernel) {
  return kernel == CorrelatorKernel::avx512 ? Geometry{32, 32} : Geometry{16, 16};
}

double wrap_units(double units, double period) {
  double c = std::fmod(units, period);
  if (c < 0.0) c += period;
  return c;
}

/// Whether this CPU can run a kernel.
bool cpu_has(CorrelatorKernel k) {
  switch (k) {
    case CorrelatorKernel::portable:
      return true;
#if defined(__x86_64__)
    case CorrelatorKernel::avx2:
      return __builtin_cpu_supports("avx2");
    case CorrelatorKernel::avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512vnni");
#endif
#if defined(__aarch64__)
    case CorrelatorKernel::neon:
      return true;  // Advanced SIMD is part of every AArch64 CPU
#endif
    default:
      return false;
  }
}

std::string available_names() {
  std::string s;
  for (CorrelatorKernel k : available_correlator_kernels())
    s += std::string(s.empty() ? "" : ", ") + correlator_kernel_name(k);
  return s;
}

/// The kernel correlate() uses: the best one, or DEEPNAV_CORRELATOR_KERNEL, or the last
/// use_correlator_kernel(). -1: not yet decided.
std::atomic<int> g_active{-1};

}  // namespace

const char* correlator_kernel_name(CorrelatorKernel k) {
  switch (k) {
    case CorrelatorKernel::portable:
      return "portable";
    case CorrelatorKernel::avx2:
      return "avx2";
    case CorrelatorKernel::avx512:
      return "avx512";
    case CorrelatorKernel::neon:
      return "neon";
  }
  return "?";
}

CorrelatorKernel correlator_kernel_named(const std::string& name) {
  for (CorrelatorKernel k :
       {CorrelatorKernel::portable, CorrelatorKernel::avx2, CorrelatorKernel::avx512, CorrelatorKernel::neon}) {
    if (name != correlator_kernel_name(k)) continue;
    if (!cpu_has(k))
      throw std::invalid_argument("correlator kernel '" + name +
                                  "' cannot run on this CPU (available: " + available_names() + ")");
    return k;
  }
  throw std::invalid_argument("unknown correlator kernel '" + name + "' (portable, avx2, avx512, neon)");
}

std::vector<CorrelatorKernel> available_correlator_kernels() {
  std::vector<CorrelatorKernel> k;
  for (CorrelatorKernel c :
       {CorrelatorKernel::portable, CorrelatorKernel::neon, CorrelatorKernel::avx2, CorrelatorKernel::avx512})
    if (cpu_has(c)) k.push_back(c);
  return k;
}

CorrelatorKernel fastest_correlator_kernel() {
  static const CorrelatorKernel best = available_correlator_kernels().back();
  return best;
}

CorrelatorKernel best_correlator_kernel() {
  int k = g_active.load(std::memory_order_relaxed);
  if (k < 0) {
    CorrelatorKernel chosen = fastest_correlator_kernel();
    if (const char* env = std::getenv("DEEPNAV_CORRELATOR_KERNEL"); env != nullptr && *env != '\0')
      chosen = correlator_kernel_named(env);
    int expected = -1;
    g_active.compare_exchange_strong(expected, static_cast<int>(chosen));
    k = g_active.load();
  }
  return static_cast<CorrelatorKernel>(k);
}

void use_correlator_kernel(CorrelatorKernel kernel) {
  if (!cpu_has(kernel))
    throw std::invalid_argument(std::string("correlator kernel '") + correlator_kernel_name(kernel) +
                                "' cannot run on this CPU (available: " + available_names() + ")");
  g_active.store(static_cast<int>(kernel));
}

void deinterleave(const Sample* x, int n, std::int16_t* i, std::int16_t* q) {
  int k = 0;
#if defined(__x86_64__)
  if (best_correlator_kernel() == CorrelatorKernel::avx512) k = deinterleave_avx512(x, n, i, q);
#endif
  for (; k < n; ++k) {
    i[k] = x[k].real();
    q[k] = x[k].imag();
  }
}

void prepare_for_correlation(SampleBlock& block) {
  const auto n = static_cast<int>(block.samples.size());
  block.magnitude_bits = sample_magnitude_bits(block.samples.data(), n);
  if (!correlator_reads_planar_input()) {
    block.planar.clear();
    return;
  }
  block.planar.resize(2 * block.samples.size());
  deinterleave(block.samples.data(), n, block.planar.data(), block.planar.data() + n);
}

bool correlator_reads_planar_input() { return best_correlator_kernel() == CorrelatorKernel::avx512; }

int sample_magnitude_bits(const Sample* samples, int n) {
  return n > 0 ? sample_bits(best_correlator_kernel(), samples, n) : 0;
}

CorrelatorSums correlate(const Sample* samples, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                         const CaCodeChips& noise_code) {
  return correlate(best_correlator_kernel(), CorrelatorInput{samples}, n, s, code, noise_code);
}

CorrelatorSums correlate(const CorrelatorInput& input, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                         const CaCodeChips& noise_code) {
  return correlate(best_correlator_kernel(), input, n, s, code, noise_code);
}

CorrelatorSums correlate(CorrelatorKernel kernel, const Sample* samples, int n, const CorrelatorSpan& s,
                         const CaCodeChips& code, const CaCodeChips& noise_code) {
  return correlate(kernel, CorrelatorInput{samples}, n, s, code, noise_code);
}

CorrelatorSums correlate(CorrelatorKernel kernel, const CorrelatorInput& input, int n, const CorrelatorSpan& s,
                         const CaCodeChips& code, const CaCodeChips& noise_code) {
  if (n <= 0) return {};
  if (!(s.code_step_chips > 0.0 && s.code_step_chips <= 2.0))
    throw std::invalid_argument("correlate: code step per sample must be in (0, 2] chips, got " +
                                std::to_string(s.code_step_chips));
  return correlate_padded(kernel, input, n, s, table_for(code).view(), table_for(noise_code).view());
}

namespace correlator_detail {

CorrelatorSums correlate_padded(CorrelatorKernel kernel, const CorrelatorInput& input, int n, const CorrelatorSpan& s,
                                const PaddedCode& code, const PaddedCode& noise) {
  const Sample* samples = input.samples;
  CorrelatorSums out;
  if (n <= 0) return out;
  const bool very = s.very_spacing_chips > 0.0;

  Setup su{};
  su.taps = very ? 5 : 3;
  su.noise = s.noise_tap;
  const auto tap = [](double entries) {
    return static_cast<std::int16_t>(std::clamp<long long>(std::llround(entries * 2048.0), -32000, 32000));
  };
  su.d[0] = tap(0.5 * s.spacing_chips);
  su.d[1] = 0;
  su.d[2] = static_cast<std::int16_t>(-su.d[0]);
  su.d[3] = very ? tap(0.5 * s.very_spacing_chips) : std::int16_t{0};
  su.d[4] = static_cast<std::int16_t>(-su.d[3]);
  int reach = 0;
  for (int t = 0; t < su.taps; ++t) reach = std::max(reach, std::abs(static_cast<int>(su.d[t])));
  su.h = std::max(1, (reach + 2047) / 2048);
  su.period = code.period;
  su.code16 = code.l16;
  su.noise16 = noise.l16;
  su.code8 = code.l8;
  su.noise8 = noise.l8;
  const auto inc = static_cast<std::int64_t>(std::llround(s.code_step_chips * kCodeOne));
  const std::int64_t wrap = std::int64_t{code.period} << kCodeFracBits;

  // A SIMD kernel needs every tap of a block inside its window: the block's first
  // position (fraction < 1 entry) plus h entries either side plus (block - 1) steps.
  if (kernel != CorrelatorKernel::portable) {
    const Geometry g = geometry(kernel);
    const std::int64_t need = (std::int64_t{1} + 2 * su.h) * (std::int64_t{1} << kCodeFracBits) + (g.block - 1) * inc;
    if (need > (std::int64_t{g.window} << kCodeFracBits) || su.h > kPad / 2) kernel = CorrelatorKernel::portable;
  }

  if (s.magnitude_bits > 16) throw std::invalid_argument("correlate: magnitude_bits must be at most 16");
  const int bits = s.magnitude_bits >= 0 ? s.magnitude_bits : sample_bits(kernel, samples, n);
  const bool small = bits <= kSmallBits;
  const CarrierTable& ct = carrier_table(bits);
  su.cos_tab = ct.cos_tab.data();
  su.sin_tab = ct.sin_tab.data();
  const bool planar = input.i != nullptr && input.q != nullptr;
  const KernelFn fn = pick_kernel(kernel, su.taps, small, planar, su.noise);
  const Input in{samples, planar ? input.i : nullptr, planar ? input.q : nullptr};

  const auto dphi = static_cast<std::uint32_t>(std::llround(s.carrier_step_cycles * kCarrierOne));
  Acc acc{};
  for (int k0 = 0; k0 < n; k0 += kRun) {
    const int m = std::min(kRun, n - k0);
    Run run{};
    const double carrier = s.carrier_phase_cycles + k0 * s.carrier_step_cycles;
    run.phi0 = static_cast<std::uint32_t>(std::llround((carrier - std::floor(carrier)) * kCarrierOne)) &
               ((1u << kCarrierBits) - 1u);
    run.dphi = dphi;
    run.pos0 = std::llround(wrap_units(s.code_phase_chips + k0 * s.code_step_chips, code.period) * kCodeOne);
    if (run.pos0 >= wrap) run.pos0 -= wrap;
    run.inc = inc;
    run.wrap = wrap;
    fn(in.at(k0), m, run, su, acc);
  }
  const auto sum = [&](int t) {
    return std::complex<double>(static_cast<double>(acc[t][0]) * ct.scale, static_cast<double>(acc[t][1]) * ct.scale);
  };
  out.early = sum(0);
  out.prompt = sum(1);
  out.late = sum(2);
  if (very) {
    out.very_early = sum(3);
    out.very_late = sum(4);
  }
  if (s.noise_tap) out.noise = sum(kNoise);
  return out;
}

}  // namespace correlator_detail

CorrelatorSums correlate_reference(const Sample* samples, int n, const CorrelatorSpan& s, const CaCodeChips& code,
                                   const CaCodeChips& noise_code) {
  CorrelatorSums out;
  const auto level = [](const CaCodeChips& c, double chips) {
    return static_cast<double>(c[static_cast<std::size_t>(std::floor(wrap_units(chips, kPeriodChips)))]);
  };
  const double half = 0.5 * s.spacing_chips, very_half = 0.5 * s.very_spacing_chips;
  for (int k = 0; k < n; ++k) {
    const double phase = s.carrier_phase_cycles + k * s.carrier_step_cycles;
    const std::complex<double> x(samples[k].real(), samples[k].imag());
    const std::complex<double> v = x * std::polar(1.0, -2.0 * M_PI * (phase - std::floor(phase)));
    const double chip = s.code_phase_chips + k * s.code_step_chips;
    out.early += v * level(code, chip + half);
    out.prompt += v * level(code, chip);
    out.late += v * level(code, chip - half);
    if (s.very_spacing_chips > 0.0) {
      out.very_early += v * level(code, chip + very_half);
      out.very_late += v * level(code, chip - very_half);
    }
    out.noise += v * level(noise_code, chip);
  }
  return out;
}

}  // namespace deepnav
