#include "receiver/acquisition/galileo_acquisition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "receiver/acquisition/e1_code_phase_refinement.hpp"
#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/e1_modulation.hpp"
#include "signals/galileo/galileo_constants.hpp"
#include "signals/sim/gaussian_noise.hpp"

namespace deepnav {
namespace {

using galileo::kE1CodeLength_chips;

/// One Galileo satellite in a test signal: code phase (chips) at the first sample.
struct E1Truth {
  int prn = 0;
  double cn0_dbhz = 45.0;
  double doppler_hz = 0.0;
  double code_phase_chips = 0.0;
};

/// The E1 OS signal of `sats` (E1-B with random data symbols, E1-C with CS25, both CBOC as
/// transmitted) in white Gaussian noise of N0 = 1, as int16 samples: complex baseband, or real
/// samples at `if_hz` (I only).
std::vector<Sample> e1_signal(const std::vector<E1Truth>& sats, double fs, double if_hz, bool real, int ms,
                              std::uint64_t seed) {
  const auto n = static_cast<std::size_t>(fs * ms / 1000.0);
  std::vector<float> i(n, 0.0f), q(n, 0.0f);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (const E1Truth& s : sats) {
    // Complex: C = A^2 over N0 = 1; real: C = A^2 / 2.
    const double amplitude = std::sqrt((real ? 2.0 : 1.0) * std::pow(10.0, s.cn0_dbhz / 10.0));
    const double chips_per_sample = galileo::kE1CodeRate_cps * (1.0 + s.doppler_hz / galileo::kE1_Hz) / fs;
    const double carrier_phase = 2.0 * std::numbers::pi * uniform(rng);
    const auto& code_b = galileo::e1b_code_chips(s.prn);
    const auto& code_c = galileo::e1c_code_chips(s.prn);
    const auto& secondary = galileo::e1c_secondary_chips();
    std::vector<int> symbols(static_cast<std::size_t>(ms / 4 + 2));
    for (int& symbol : symbols) symbol = uniform(rng) < 0.5 ? 1 : -1;
    const auto secondary_offset = static_cast<std::size_t>(uniform(rng) * galileo::kE1cSecondaryLength_chips);
    // Into [0, one code): a truth given as a negative phase (a delay of more than a period)
    // would otherwise index period -1; the tests compare code phases modulo the code.
    const double start_chips =
        s.code_phase_chips - kE1CodeLength_chips * std::floor(s.code_phase_chips / kE1CodeLength_chips);
    for (std::size_t k = 0; k < n; ++k) {
      const double phase = start_chips + static_cast<double>(k) * chips_per_sample;
      const auto period = static_cast<std::size_t>(std::floor(phase / kE1CodeLength_chips));
      const auto chip = static_cast<std::size_t>(std::floor(phase)) - period * kE1CodeLength_chips;
      const int e1b = code_b[chip] * symbols[period];
      const int e1c = code_c[chip] * secondary[(period + secondary_offset) % galileo::kE1cSecondaryLength_chips];
      const double v = amplitude * galileo::e1_composite(e1b, e1c, phase);
      const double angle =
          2.0 * std::numbers::pi * (if_hz + s.doppler_hz) * static_cast<double>(k) / fs + carrier_phase;
      i[k] += static_cast<float>(v * std::cos(angle));
      if (!real) q[k] += static_cast<float>(v * std::sin(angle));
    }
  }
  GaussianNoise noise(seed + 1);
  const auto sigma = static_cast<float>(std::sqrt(fs / 2.0));
  noise.add_real(i, sigma);
  if (!real) noise.add_real(q, sigma);
  const float scale = 64.0f / sigma;  // noise at 1/64 of its RMS resolution, like a 12-bit front end
  std::vector<Sample> out(n);
  for (std::size_t k = 0; k < n; ++k)
    out[k] = {static_cast<std::int16_t>(std::lround(i[k] * scale)),
              static_cast<std::int16_t>(std::lround(q[k] * scale))};
  return out;
}

/// |a - b| on the 4092-chip circle.
double chip_error(double a, double b) {
  const double d = std::fmod(std::abs(a - b), static_cast<double>(kE1CodeLength_chips));
  return std::min(d, kE1CodeLength_chips - d);
}

/// Each truth detected at its PRN within a quarter chip and half a Doppler bin, C/N0 within
/// 2.5 dB (the BOC(1,1) replica sees 10/11 of the CBOC power: -0.4 dB); nothing else detected.
void expect_found(const std::vector<GalileoAcquisitionResult>& results, const std::vector<E1Truth>& truths,
                  const GalileoAcquisitionConfig& cfg) {
  std::set<int> present;
  for (const auto& t : truths) present.insert(t.prn);
  for (const auto& r : results) {
    EXPECT_EQ(r.satellite.system, GnssSystem::galileo);
    const auto t =
        std::find_if(truths.begin(), truths.end(), [&](const E1Truth& e) { return e.prn == r.satellite.prn; });
    if (t == truths.end()) {
      EXPECT_FALSE(r.detected) << r.satellite.to_string() << " is absent (statistic " << r.statistic << ", threshold "
                               << r.threshold << ")";
      continue;
    }
    ASSERT_TRUE(r.detected) << r.satellite.to_string() << " statistic " << r.statistic << " threshold " << r.threshold;
    EXPECT_LE(chip_error(r.code_phase_chips, t->code_phase_chips), 0.25)
        << r.satellite.to_string() << " code phase " << r.code_phase_chips << " truth " << t->code_phase_chips;
    EXPECT_LE(std::abs(r.doppler_hz - t->doppler_hz), cfg.doppler_step_hz / 2)
        << r.satellite.to_string() << " Doppler " << r.doppler_hz;
    EXPECT_NEAR(r.cn0_dbhz, t->cn0_dbhz - 0.4, 2.5) << r.satellite.to_string();
    // The delay is where the code epoch falls: the code phase seen from the other side.
    const double delay_chips = r.delay_samples * galileo::kE1CodeRate_cps / cfg.sample_rate_hz;
    EXPECT_LE(chip_error(kE1CodeLength_chips - delay_chips, r.code_phase_chips), 1e-6);
  }
}

GalileoAcquisitionConfig config(double fs, double if_hz, std::vector<int> prns) {
  GalileoAcquisitionConfig cfg;
  cfg.sample_rate_hz = fs;
  cfg.if_hz = if_hz;
  cfg.prns = std::move(prns);
  return cfg;
}

TEST(GalileoAcquisition, FindsE1At4MspsComplexWithCodePhaseDopplerAndCn0) {
  const std::vector<E1Truth> truths{{11, 45.0, 1730.0, 1234.3}, {25, 45.0, -3115.0, 3907.81}};
  const auto cfg = config(4e6, 0.0, {3, 11, 19, 25, 36});
  GalileoAcquisition acq(cfg);
  EXPECT_EQ(acq.samples_needed(), 5 * 16000);
  const auto samples = e1_signal(truths, cfg.sample_rate_hz, 0.0, false, 20, 7);
  const auto results = acq.search(samples);
  ASSERT_EQ(results.size(), 5u);
  expect_found(results, truths, cfg);
  // The refined values are far better than the bounds above.
  for (const auto& r : results)
    for (const auto& t : truths)
      if (r.satellite.prn == t.prn) {
        EXPECT_LE(chip_error(r.code_phase_chips, t.code_phase_chips), 0.05) << r.satellite.to_string();
        EXPECT_NEAR(r.doppler_hz, t.doppler_hz, 15.0) << r.satellite.to_string();
      }
}

TEST(GalileoAcquisition, FindsE1At12MspsRealIf) {
  const std::vector<E1Truth> truths{{19, 45.0, -2400.0, 3001.7}};
  const auto cfg = config(12e6, 3e6, {5, 19, 30});
  GalileoAcquisition acq(cfg);
  const auto samples = e1_signal(truths, cfg.sample_rate_hz, cfg.if_hz, true, 20, 11);
  const auto results = acq.search(samples);
  expect_found(results, truths, cfg);
}

TEST(GalileoAcquisition, NothingDetectedInNoiseAlone) {
  const auto cfg = config(4e6, 0.0, {1, 2, 3, 4, 5, 6, 7, 8});
  GalileoAcquisition acq(cfg);
  const auto results = acq.search(e1_signal({}, cfg.sample_rate_hz, 0.0, false, 20, 3));
  expect_found(results, {}, cfg);
}

// The grid's lags are 1/4 chip apart at 4 Msps. Truth halfway between two lags puts the main
// peak's best cell 1/8 chip off its top (0.62 of its amplitude, 4.2 dB down); truth at a lag
// plus 0.045 sample puts a lag exactly on a side lobe's extreme (-0.5, 6 dB down). At 40
// dB-Hz noise moves cells by about a dB: the code phase must still be the main peak's. (At
// 4 Msps and above the main peak keeps a cell within 1/8 chip of its top, 1.8 dB above any
// side-lobe cell, so this holds in white noise even without the side-lobe check; the check
// itself is what the next test exercises.)
TEST(GalileoAcquisition, MainPeakReportedWhenSideLobesSitOnTheGrid) {
  const double fs = 4e6;
  const double samples_per_chip = fs / galileo::kE1CodeRate_cps;
  const double side_lobe_samples = 0.5 * samples_per_chip;  // 1.955
  for (const double fraction : {0.5, std::ceil(side_lobe_samples) - side_lobe_samples, 0.4, 0.6}) {
    std::vector<E1Truth> truths;
    for (int prn : {4, 9, 14, 24}) {
      // Whole samples of delay plus `fraction`: the code phase at the first sample.
      const double delay = 1000.0 * prn + fraction;
      truths.push_back({prn, 40.0, 250.0 * prn - 3000.0, kE1CodeLength_chips - delay / samples_per_chip});
    }
    auto cfg = config(fs, 0.0, {4, 9, 14, 24});
    cfg.noncoherent = 10;
    GalileoAcquisition acq(cfg);
    const auto results = acq.search(e1_signal(truths, fs, 0.0, false, 40, 100 + static_cast<int>(fraction * 100)));
    for (const auto& r : results) {
      const auto& t =
          *std::find_if(truths.begin(), truths.end(), [&](const E1Truth& e) { return e.prn == r.satellite.prn; });
      ASSERT_TRUE(r.detected) << r.satellite.to_string() << " fraction " << fraction;
      EXPECT_LE(chip_error(r.code_phase_chips, t.code_phase_chips), 0.1)
          << r.satellite.to_string() << " fraction " << fraction << ": " << r.code_phase_chips << " vs "
          << t.code_phase_chips << (r.moved_off_side_lobe ? " (moved off a side lobe)" : "");
    }
  }
}

// A coarse cell on a side lobe (half a chip from the truth, either side) is moved back to the
// main peak; one on the main peak stays there.
TEST(GalileoAcquisition, RefinementLeavesASideLobeForTheMainPeak) {
  const double fs = 4e6;
  const E1Truth truth{7, 42.0, 900.0, 2047.37};
  const auto samples = e1_signal({truth}, fs, 0.0, false, 20, 21);
  const E1CodePhaseRefiner refiner(fs, 0.0);
  for (const double offset : {-0.5, -0.45, 0.5, 0.55, 0.0, 0.1}) {
    const E1RefinedSignal r = refiner.refine(samples, truth.prn, truth.code_phase_chips + offset, 950.0, 125.0);
    EXPECT_LE(chip_error(r.code_phase_chips, truth.code_phase_chips), 0.03) << "start offset " << offset;
    EXPECT_EQ(r.moved_off_side_lobe, std::abs(offset) > 0.25) << "start offset " << offset;
    EXPECT_NEAR(r.doppler_hz, truth.doppler_hz, 10.0) << "start offset " << offset;
  }
  // The side lobe's power is a quarter of the main peak's (BOC(1,1): -1/2 at half a chip).
  const double main = refiner.correlate(samples, truth.prn, truth.code_phase_chips, truth.doppler_hz).all_periods;
  const double side = refiner.correlate(samples, truth.prn, truth.code_phase_chips + 0.5, truth.doppler_hz).all_periods;
  EXPECT_NEAR(side / main, 0.25, 0.06);
}

TEST(GalileoAcquisition, BadSettingsAndTooFewSamplesAreRefused) {
  EXPECT_THROW(GalileoAcquisition(config(2.5e6, 0.0, {})), std::invalid_argument);
  EXPECT_THROW(GalileoAcquisition(config(4e6, 2.5e6, {})), std::invalid_argument);
  EXPECT_THROW(GalileoAcquisition(config(4e6, 0.0, {51})), std::invalid_argument);
  EXPECT_THROW(GalileoAcquisition(config(4e6, 0.0, {0})), std::invalid_argument);
  auto cfg = config(4e6, 0.0, {1});
  cfg.doppler_step_hz = 500.0;
  EXPECT_THROW(GalileoAcquisition{cfg}, std::invalid_argument);
  auto memory = config(200e6, 0.0, {1});
  memory.noncoherent = 1000;  // 1000 spectra of 800000 points: 6 GB
  try {
    GalileoAcquisition too_much(memory);
    ADD_FAILURE() << "6 GB of spectra accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("MiB of spectra"), std::string::npos) << e.what();
  }
  GalileoAcquisition acq(config(4e6, 0.0, {1}));
  const std::vector<Sample> short_block(15999, Sample{1, -1});
  EXPECT_THROW(acq.search(short_block), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
