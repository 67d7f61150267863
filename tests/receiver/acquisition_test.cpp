#include "receiver/acquisition/acquisition.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include <cmath>
#include <map>
#include <set>

#include "receiver/sources/file_sample_source.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/gaussian_noise.hpp"
#include "signals/sim/satellite_signal_kernel.hpp"

namespace deepnav {
namespace {

const std::string kData = std::string(DEEPNAV_SOURCE_DIR) + "/data/";

struct Expected {
  double doppler_hz, delay_samples;
};

std::vector<Sample> read_all(FileSampleSourceOptions o, std::int64_t max_samples) {
  FileSampleSource src(std::move(o));
  std::vector<Sample> s(static_cast<std::size_t>(max_samples));
  std::size_t got = 0;
  while (got < s.size()) {
    const auto n = src.read(std::span<Sample>(s.data() + got, s.size() - got));
    if (n == 0) break;
    got += n;
  }
  s.resize(got);
  return s;
}

/// Every expected PRN within +-250 Hz and +-2 samples; nothing outside expected + allowed.
void check_capture(const std::string& file, SampleFormat format, double fs, double if_hz, bool inverted,
                   const std::map<int, Expected>& expected, const std::set<int>& also_present, double doppler_max,
                   int noncoherent = 10) {
  AcquisitionConfig cfg;
  cfg.sample_rate_hz = fs;
  cfg.if_hz = if_hz;
  cfg.doppler_max_hz = doppler_max;
  cfg.noncoherent = noncoherent;
  Acquisition acq(cfg);
  FileSampleSourceOptions o;
  o.path = kData + file;
  o.format = format;
  o.sample_rate_hz = fs;
  o.intermediate_frequency_hz = if_hz;
  o.inverted_spectrum = inverted;
  const auto results = acq.search(read_all(o, acq.samples_needed()));
  for (const auto& r : results) {
    if (const auto it = expected.find(r.prn); it != expected.end()) {
      EXPECT_TRUE(r.detected) << file << " PRN " << r.prn << " statistic " << r.statistic << " threshold "
                              << r.threshold;
      EXPECT_NEAR(r.doppler_hz, it->second.doppler_hz, 250.0) << file << " PRN " << r.prn;
      double d = std::abs(r.delay_samples - it->second.delay_samples);
      d = std::min(d, fs / 1000.0 - d);
      EXPECT_LE(d, 2.0) << file << " PRN " << r.prn << " delay " << r.delay_samples;
    } else if (!also_present.count(r.prn)) {
      EXPECT_FALSE(r.detected) << file << " PRN " << r.prn << " reported but not present (statistic " << r.statistic
                               << ", threshold " << r.threshold << ")";
    }
  }
}

// Expected values: data/README.md.
const std::map<int, Expected> k4MHz{
    {31, {-190, 1159}}, {26, {650, 3599}}, {29, {-2220, 1653}}, {16, {2600, 3958}}, {32, {-3380, 2766}}};
// PRN 18 is in the 4 MHz capture too, weakly (about 37 dB-Hz at every coherent length, so it
// is not a cross-correlation): the broadcast orbits, shifted by the sidereal repeat, put it
// 16 deg above the Tokyo horizon at a Doppler matching the other satellites' clock offset.
// It may be reported; see data/README.md.
const std::set<int> k4MHzWeak{18};

TEST(Acquisition, RealSky4MHzComplexInvertedSpectrum) {
  check_capture("L1_20211202_084700_4MHz_IQ.bin", SampleFormat::ibyte, 4e6, 0.0, true, k4MHz, k4MHzWeak, 5000.0);
}

TEST(Acquisition, RealSky4MHzWithAFifteenKilohertzSearch) {
  check_capture("L1_20211202_084700_4MHz_IQ.bin", SampleFormat::ibyte, 4e6, 0.0, true, k4MHz, k4MHzWeak, 15000.0);
}

TEST(Acquisition, RealSky12MHzRealIf) {
  const std::map<int, Expected> expected{{5, {140, 5611}},     {13, {-230, 6004}}, {20, {-1370, 8172}},
                                         {15, {1730, 9317}},   {2, {-2740, 5328}}, {30, {-1880, 4719}},
                                         {11, {-3280, 11004}}, {18, {3280, 6580}}, {29, {-2030, 9075}}};
  check_capture("L1_20211125_004000_12MHz_I.bin", SampleFormat::byte, 12e6, 3e6, false, expected, {}, 5000.0);
}

TEST(Acquisition, GnssSdrReferenceFile) {
  check_capture("GPS_L1_CA_ID_1_Fs_4Msps_2ms.dat", SampleFormat::gr_complex, 4e6, 0.0, false, {{1, {1680, 524}}}, {},
                5000.0, 2);
}

/// One satellite at a known delay and Doppler in complex white noise (N0 = 1).
std::vector<Sample> synthetic(int prn, double cn0_dbhz, double doppler_hz, double delay_samples, double fs, int ms,
                              std::uint64_t seed) {
  const int n = static_cast<int>(fs * ms / 1000.0);
  std::vector<float> i(static_cast<std::size_t>(n), 0.0f), q(i.size(), 0.0f), scratch(i.size());
  if (cn0_dbhz > 0.0) {
    SignalSegment s;
    const double code_rate = gps::kCodeRate_cps * (1.0 + doppler_hz / gps::kL1_Hz);
    s.code_step_chips = code_rate / fs;
    s.code_phase_chips = std::fmod(1023.0 - delay_samples * s.code_step_chips + 1023.0 * 8, 1023.0);
    s.carrier_step_cycles = doppler_hz / fs;
    s.amplitude = static_cast<float>(std::pow(10.0, cn0_dbhz / 20.0));
    add_satellite_segment(i.data(), q.data(), n, s, ca_code_chips(prn), scratch.data());
  }
  GaussianNoise noise(seed);
  const float sigma = static_cast<float>(std::sqrt(fs / 2.0));
  noise.add_real(i, sigma);
  noise.add_real(q, sigma);
  // The int16 samples hold the noise at ~1/16 of its RMS resolution, like a 12-bit front end.
  const float scale = 64.0f / sigma;
  std::vector<Sample> out(i.size());
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = {static_cast<std::int16_t>(std::lround(i[k] * scale)),
              static_cast<std::int16_t>(std::lround(q[k] * scale))};
  return out;
}

TEST(Acquisition, SyntheticSignalFoundWithCorrectDelayDopplerAndCn0) {
  const double fs = 4.092e6;
  AcquisitionConfig cfg;
  cfg.sample_rate_hz = fs;
  cfg.prns = {7, 8};
  Acquisition acq(cfg);
  for (double cn0 : {40.0, 45.0}) {
    const auto x = synthetic(7, cn0, 1234.0, 1717.0, fs, 10, 11);
    const auto r = acq.search(x);
    ASSERT_TRUE(r[0].detected) << cn0;
    EXPECT_NEAR(r[0].delay_samples, 1717.0, 1.0);
    EXPECT_NEAR(r[0].doppler_hz, 1234.0, cfg.doppler_step_hz > 0 ? cfg.doppler_step_hz / 2 : 333.0);
    EXPECT_NEAR(r[0].code_phase_chips, std::fmod(1023.0 - 1717.0 * 1.023e6 / fs + 1023.0, 1023.0), 0.3);
    EXPECT_NEAR(r[0].cn0_dbhz, cn0, 2.0);
    EXPECT_FALSE(r[1].detected);  // PRN 8 is absent
  }
}

TEST(Acquisition, FractionalDelaysAtRatesWhoseBlocksAreStretched) {
  // 4092 and 2046 samples per ms have the factors 11 and 31: the search runs on a block
  // stretched to 4096 / 2048 samples. Delays and C/N0 must come back in the input's samples
  // without bias, whatever the fraction of a sample the code epoch falls on.
  for (double fs : {4.092e6, 2.046e6}) {
    AcquisitionConfig cfg;
    cfg.sample_rate_hz = fs;
    cfg.prns = {11};
    Acquisition acq(cfg);
    double error_sum = 0.0;
    int count = 0;
    for (double delay : {301.0, 301.25, 301.5, 301.75, 1500.5, 1900.25}) {
      const auto r = acq.search(synthetic(11, 45.0, -2200.0, delay, fs, 10, 77 + count));
      ASSERT_TRUE(r[0].detected) << fs << " " << delay;
      EXPECT_NEAR(r[0].delay_samples, delay, 0.75) << fs;
      EXPECT_NEAR(r[0].doppler_hz, -2200.0, 150.0) << fs << " " << delay;
      EXPECT_NEAR(r[0].cn0_dbhz, 45.0, 1.5) << fs << " " << delay;
      error_sum += r[0].delay_samples - delay;
      ++count;
    }
    EXPECT_NEAR(error_sum / count, 0.0, 0.3) << fs;  // no systematic offset
  }
}

TEST(Acquisition, ObjectsMadeAndSearchedInSeveralThreadsAtOnce) {
  // Benchmarks run several receivers in threads of one process; FFTW's planner is not
  // thread-safe, so plans are made under a lock (without it this aborts inside FFTW).
  std::vector<std::thread> threads;
  std::atomic<int> found{0};
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int k = 0; k < 6; ++k) {
        AcquisitionConfig cfg;
        cfg.sample_rate_hz = (k % 2 == 0) ? 2.046e6 : 2.5e6;
        cfg.prns = {7};
        cfg.noncoherent = 2;
        cfg.doppler_max_hz = 1000.0;
        Acquisition acq(cfg);
        const auto r = acq.search(synthetic(7, 50.0, 300.0, 100.0 + t, cfg.sample_rate_hz, 2, 500 + 10 * t + k));
        found += r[0].detected ? 1 : 0;
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_EQ(found.load(), 24);
}

TEST(Acquisition, FalseAlarmRateFollowsPfa) {
  // Pure noise, one PRN, a small grid: a generous Pfa makes the rate measurable quickly.
  AcquisitionConfig cfg;
  cfg.sample_rate_hz = 2.046e6;
  cfg.prns = {3};
  cfg.doppler_max_hz = 1000.0;
  cfg.noncoherent = 2;
  cfg.pfa = 0.2;
  Acquisition acq(cfg);
  int alarms = 0;
  const int trials = 150;
  for (int t = 0; t < trials; ++t) alarms += acq.search(synthetic(3, 0.0, 0.0, 0.0, 2.046e6, 2, 1000 + t))[0].detected;
  const double expected = cfg.pfa * trials;
  EXPECT_GT(alarms, expected / 3.0);
  EXPECT_LT(alarms, expected * 3.0);
}

TEST(Acquisition, GammaTailAndThreshold) {
  EXPECT_NEAR(gamma_upper_tail(1, 3.0), std::exp(-3.0), 1e-15);
  EXPECT_NEAR(gamma_upper_tail(2, 3.0), 4.0 * std::exp(-3.0), 1e-15);
  const double thr = acquisition_threshold(10, 1e5, 1e-3);
  EXPECT_NEAR(1.0 - std::pow(1.0 - gamma_upper_tail(10, thr), 1e5), 1e-3, 1e-6);
}

TEST(Acquisition, BadSettingsAreRejected) {
  AcquisitionConfig cfg;
  cfg.coherent_ms = 11;
  EXPECT_THROW(Acquisition{cfg}, std::invalid_argument);
  cfg = AcquisitionConfig{};
  cfg.prns = {33};
  EXPECT_THROW(Acquisition{cfg}, std::invalid_argument);
  cfg = AcquisitionConfig{};
  Acquisition acq(cfg);
  std::vector<Sample> too_short(100);
  EXPECT_THROW(acq.search(too_short), std::invalid_argument);
}

}  // namespace
}  // namespace deepnav
