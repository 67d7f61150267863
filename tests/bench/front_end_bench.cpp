// Cost of the synthesizer's front end per sample, on 1 ms blocks at 4.092 Msps:
// thermal noise, each jammer type, and AGC + 2-bit quantization + ibyte packing.
// Items processed = samples, so the reported items_per_second inverts to ns/sample.
#include <benchmark/benchmark.h>

#include <complex>
#include <cstdint>
#include <vector>

#include "signals/sim/front_end.hpp"
#include "signals/sim/gaussian_noise.hpp"
#include "signals/sim/indexed_noise.hpp"
#include "signals/sim/jammer.hpp"

namespace {

constexpr double kFs = 4.092e6;
constexpr std::size_t kBlock = 4092;

void BM_ComplexThermalNoise(benchmark::State& state) {
  deepnav::IndexedNoise noise(1);
  std::vector<std::complex<float>> block(kBlock);
  std::int64_t first = 0;
  for (auto _ : state) {
    noise.add_complex(block, first, 1.0f);
    first += kBlock;
    benchmark::DoNotOptimize(block.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBlock));
}
BENCHMARK(BM_ComplexThermalNoise);

void BM_Jammer(benchmark::State& state) {
  deepnav::JammerConfig c;
  c.type = static_cast<deepnav::JammerType>(state.range(0));
  c.js_db = 40;
  c.center_offset_hz = 100e3;
  c.bandwidth_hz = state.range(1);
  c.sweep_period_s = 100e-6;
  c.duty_cycle = 0.3;
  c.pulse_rate_hz = 1000;
  deepnav::Jammer jammer(c, kFs, 0.0, 45.0, 1);
  std::vector<std::complex<float>> block(kBlock);
  std::int64_t first = 0;
  for (auto _ : state) {
    jammer.add_to(block, first);
    first += kBlock;
    benchmark::DoNotOptimize(block.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBlock));
  state.SetLabel(deepnav::to_string(c.type) +
                 (c.bandwidth_hz > 0 ? " B=" + std::to_string(state.range(1) / 1000) + "kHz" : ""));
}
BENCHMARK(BM_Jammer)
    ->Args({0, 0})
    ->Args({1, 2000000})
    ->Args({2, 2000000})
    ->Args({2, 200000})
    ->Args({3, 0})
    ->Args({3, 2000000});

void BM_AgcQuantizePack(benchmark::State& state) {
  deepnav::FrontEndConfig c;
  c.sample_rate_hz = kFs;
  // 0 ibyte, 1 ishort, 2 gr_complex, 3 byte, 4 cu8, 5 packed (two_bit_packed: real 2-bit codes, four a byte)
  c.format = deepnav::SampleFormat{static_cast<deepnav::SampleKind>(state.range(0)), {}};
  c.adc.bits = static_cast<int>(state.range(1));
  c.thermal_noise = false;
  deepnav::FrontEnd fe(c, 1);
  std::vector<std::complex<float>> block(kBlock);
  deepnav::GaussianNoise(3).fill_complex(block, 1000.0f);
  std::vector<std::byte> out;
  std::int64_t first = 0;
  for (auto _ : state) {
    fe.process(block, first, out);
    first += kBlock;
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBlock));
  state.SetLabel(std::string(deepnav::to_string(c.format)) + " " + std::to_string(c.adc.bits) + "-bit");
}
BENCHMARK(BM_AgcQuantizePack)->Args({0, 2})->Args({1, 12})->Args({2, 0})->Args({3, 2})->Args({4, 8})->Args({5, 2});

void BM_FrontEndNoiseQuantizePack(benchmark::State& state) {
  deepnav::FrontEndConfig c;
  c.sample_rate_hz = kFs;
  c.format = deepnav::SampleFormat::ibyte;
  c.adc.bits = 2;
  deepnav::FrontEnd fe(c, 1);
  std::vector<std::complex<float>> block(kBlock);
  std::vector<std::byte> out;
  std::int64_t first = 0;
  for (auto _ : state) {
    fe.process(block, first, out);
    first += kBlock;
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBlock));
}
BENCHMARK(BM_FrontEndNoiseQuantizePack);

}  // namespace

BENCHMARK_MAIN();
