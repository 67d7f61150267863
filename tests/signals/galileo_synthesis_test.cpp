// Galileo E1 satellites in the IF synthesizer: which are chosen, that a synthesized
// satellite's E1-B and E1-C signals correlate where its truth says, that its I/NAV symbols
// decode into the words carrying the ephemeris it was given, and that GPS-only runs are
// unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "signals/galileo/e1_codes.hpp"
#include "signals/galileo/e1_modulation.hpp"
#include "signals/galileo/inav_page.hpp"
#include "signals/galileo/inav_words.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/inav_broadcast.hpp"
#include "signals/sim/satellite_selection.hpp"

namespace deepnav {
namespace {

namespace inav = galileo::inav;
const std::string kRoot = DEEPNAV_SOURCE_DIR;

/// A folder of this process's own: ctest runs each test as its own process, in parallel.
std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("deepnav_galsynth_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

std::vector<char> read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint64_t fnv1a(const std::vector<char>& bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

Scenario mixed_scenario(double duration_s) {
  Scenario sc = load_scenario(kRoot + "/data/scenarios/static_gps_galileo_60s.yaml", kRoot);
  sc.duration_s = duration_s;
  sc.sample_rate_hz = 2.046e6;
  sc.sat_truth_rate_hz = 100;
  validate_scenario(sc);
  return sc;
}

struct TruthRow {
  std::string name;
  double t_s = 0, code_phase_chips = 0, doppler_hz = 0, pseudorange_m = 0;
};

/// The first sat_truth.csv row of satellite `name` ("E03").
TruthRow first_truth_row(const std::filesystem::path& p, const std::string& name) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) f.push_back(cell);
    if (f.size() < 9 || f[1] != name) continue;
    return TruthRow{f[1], std::stod(f[0]), std::stod(f[2]), std::stod(f[3]), std::stod(f[8])};
  }
  ADD_FAILURE() << name << " not in " << p;
  return {};
}

TEST(GalileoSynthesis, ChoosesVisibleGalileoSatellitesBesideTheSameGps) {
  const Scenario sc = mixed_scenario(1.0);
  const NavData nav = read_rinex_nav(sc.nav_file);
  const IfSynthesizer synth(sc, nav);
  int galileo = 0;
  std::vector<int> gps_prns;
  for (const auto& sat : synth.satellites()) {
    EXPECT_GE(sat.elevation_start_deg, 10.0) << sat.id.to_string();
    if (sat.id.system == GnssSystem::galileo) {
      ++galileo;
    } else {
      EXPECT_EQ(galileo, 0) << "GPS satellites come first";
      gps_prns.push_back(sat.prn);
    }
  }
  EXPECT_GE(galileo, 4);
  // The same GPS satellites as a GPS-only run of the same scenario.
  Scenario gps_only = sc;
  gps_only.systems = {GnssSystem::gps};
  std::vector<int> expected;
  const IfSynthesizer gps_synth(gps_only, nav);
  for (const auto& sat : gps_synth.satellites()) expected.push_back(sat.prn);
  EXPECT_EQ(gps_prns, expected);
}

TEST(GalileoSynthesis, NoGalileoRecordsIsAnErrorNamingTheFile) {
  Scenario sc = mixed_scenario(1.0);
  sc.nav_file = kRoot + "/data/brdc0010.22n";
  try {
    IfSynthesizer synth(sc, read_rinex_nav(sc.nav_file));
    FAIL() << "a GPS-only file was accepted for systems [gps, galileo]";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("brdc0010.22n"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Galileo"), std::string::npos) << e.what();
  }
}

TEST(GalileoSynthesis, SystemsKeyIsParsedCheckedAndWrittenBack) {
  const Scenario sc = mixed_scenario(1.0);
  EXPECT_EQ(sc.systems, (std::vector<GnssSystem>{GnssSystem::gps, GnssSystem::galileo}));
  EXPECT_NE(scenario_to_yaml(sc).find("systems: [gps, galileo]"), std::string::npos);
  const std::string base = "start_time: 2022-01-01T20:30:00\nduration_s: 1\nnav_file: data/gps_galileo_20220101.rnx\n";
  EXPECT_THROW(parse_scenario(base + "systems: [gps, glonass]\n", "t.yaml", kRoot, kRoot), std::invalid_argument);
  EXPECT_THROW(parse_scenario(base + "systems: [gps, gps]\n", "t.yaml", kRoot, kRoot), std::invalid_argument);
  EXPECT_THROW(parse_scenario(base + "systems: []\n", "t.yaml", kRoot, kRoot), std::invalid_argument);
  const Scenario gps = parse_scenario(base, "t.yaml", kRoot, kRoot);
  EXPECT_EQ(gps.systems, std::vector<GnssSystem>{GnssSystem::gps});
  EXPECT_EQ(scenario_to_yaml(gps).find("systems"), std::string::npos);
}

TEST(GalileoSynthesis, PerSatelliteCn0AndOutagesNameGalileoSatellites) {
  const std::string text =
      "start_time: 2022-01-01T20:30:00\nduration_s: 0.5\nsample_rate_hz: 2046000\n"
      "nav_file: data/gps_galileo_20220101.rnx\nsystems: [gps, galileo]\nelevation_mask_deg: 10\n"
      "trajectory: {preset: static, start: {lat_deg: 37.5665, lon_deg: 126.9780, height_m: 40}}\n"
      "cn0: {dbhz: 45, per_prn: {G02: 40, 5: 41, E03: 30}}\n"
      "outages: [{start_s: 0.2, end_s: 0.3, prns: [20, E13]}]\nsat_truth_rate_hz: 10\n";
  const Scenario sc = parse_scenario(text, "t.yaml", kRoot, kRoot);
  EXPECT_EQ(sc.cn0.per_prn_dbhz.at(2), 40.0);
  EXPECT_EQ(sc.cn0.per_prn_dbhz.at(5), 41.0);
  EXPECT_EQ(sc.cn0.galileo_per_svid_dbhz.at(3), 30.0);
  ASSERT_EQ(sc.outages.size(), 1u);
  EXPECT_EQ(sc.outages[0].prns, std::vector<int>{20});
  EXPECT_EQ(sc.outages[0].galileo_prns, std::vector<int>{13});
  // Written back and read again: the same keys.
  const Scenario again = parse_scenario(scenario_to_yaml(sc), "again.yaml", kRoot, kRoot);
  EXPECT_EQ(again.cn0.galileo_per_svid_dbhz, sc.cn0.galileo_per_svid_dbhz);
  EXPECT_EQ(again.outages[0].galileo_prns, sc.outages[0].galileo_prns);
  EXPECT_EQ(again.outages[0].prns, sc.outages[0].prns);
  EXPECT_THROW(parse_scenario(text + "prns: [E51]\n", "t.yaml", kRoot, kRoot), std::invalid_argument);
  {
    // prns restricts each system it names.
    const Scenario only = parse_scenario(text + "prns: [G02, 5, E03]\n", "t.yaml", kRoot, kRoot);
    EXPECT_EQ(only.prns, (std::vector<int>{2, 5}));
    EXPECT_EQ(only.galileo_prns, std::vector<int>{3});
    EXPECT_EQ(parse_scenario(scenario_to_yaml(only), "again.yaml", kRoot, kRoot).galileo_prns, only.galileo_prns);
    std::vector<std::string> names;
    const IfSynthesizer synth(only, read_rinex_nav(only.nav_file));
    for (const auto& sat : synth.satellites()) names.push_back(sat.id.to_string());
    EXPECT_EQ(names, (std::vector<std::string>{"G02", "G05", "E03"}));
  }

  const auto dir = fresh_dir("overrides");
  SynthesisOptions options;
  options.threads = 1;
  IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir.string(), options);
  std::ifstream in(dir / "sat_truth.csv");
  std::string line;
  std::getline(in, line);
  int e03 = 0, e13_off = 0, g20_off = 0, e13_on = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    const double t = std::stod(f[0]);
    if (f[1] == "E03") {
      EXPECT_NEAR(std::stod(f[5]), 30.0, 0.5);  // the override plus the antenna pattern (0 dB by default)
      ++e03;
    }
    const bool in_window = t >= 0.2 - 1e-9 && t < 0.3 - 1e-9;
    if (f[1] == "E13") (in_window ? e13_off : e13_on) += f[14] == (in_window ? "0" : "1");
    if (f[1] == "G20" && in_window) g20_off += f[14] == "0";
  }
  EXPECT_EQ(e03, 5);
  EXPECT_EQ(e13_off, 1);
  EXPECT_EQ(g20_off, 1);
  EXPECT_EQ(e13_on, 4);
}

/// A GPS-only scenario with the error world and multipath: the IF and truth files of a
/// 0.3 s run, as the synthesizer wrote them before Galileo (FNV-1a 64 of each file).
TEST(GalileoSynthesis, GpsOnlyScenarioBytesUnchanged) {
  Scenario sc = load_scenario(kRoot + "/data/scenarios/land_circle_aided_90s_open_sky.yaml", kRoot);
  sc.duration_s = 0.3;
  validate_scenario(sc);
  const auto dir = fresh_dir("gps_golden");
  SynthesisOptions options;
  options.threads = 1;
  IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir.string(), options);
  EXPECT_EQ(fnv1a(read_bytes(dir / if_file_name(sc.format))), 0xf4114f3ede4cc2e1ULL);
  EXPECT_EQ(fnv1a(read_bytes(dir / "truth.csv")), 0xfc29429110233865ULL);
  EXPECT_EQ(fnv1a(read_bytes(dir / "sat_truth.csv")), 0xdf018a10b8b48177ULL);
}

/// A synthesized IF and the truth of one Galileo satellite, with its samples' carrier wiped
/// off by the truth's Doppler (IF 0) and the code rate that Doppler implies.
struct GalileoCapture {
  Scenario sc;
  NavData nav;
  SynthesizedSatellite sat;
  TruthRow truth;
  std::vector<std::complex<float>> samples;  ///< carrier wiped
  double chips_per_sample = 0.0;

  explicit GalileoCapture(double duration_s) : sc(mixed_scenario(duration_s)), nav(read_rinex_nav(sc.nav_file)) {
    const auto dir = fresh_dir("capture");
    SynthesisOptions options;
    options.threads = 2;
    const SynthesisSummary summary = IfSynthesizer(sc, nav).run(dir.string(), options);
    for (const auto& s : summary.satellites) {
      if (s.id.system == GnssSystem::galileo) {
        sat = s;  // the highest Galileo satellite
        break;
      }
    }
    truth = first_truth_row(dir / "sat_truth.csv", sat.id.to_string());
    const std::vector<char> raw = read_bytes(dir / if_file_name(sc.format));
    const double fs = sc.sample_rate_hz;
    chips_per_sample = 1.023e6 * (1.0 + truth.doppler_hz / gps::kL1_Hz) / fs;
    samples.resize(raw.size() / 2);
    const std::complex<double> step = std::polar(1.0, -2.0 * M_PI * truth.doppler_hz / fs);
    std::complex<double> z = 1.0;
    for (std::size_t n = 0; n < samples.size(); ++n, z *= step) {
      if (n % 4096 == 0) z = std::polar(1.0, -2.0 * M_PI * truth.doppler_hz * static_cast<double>(n) / fs);
      const std::complex<double> x(raw[2 * n], raw[2 * n + 1]);
      samples[n] = std::complex<float>(x * z);
    }
  }

  /// First sample at which a new code period starts (code phase back to 0).
  std::size_t first_period_sample() const {
    return static_cast<std::size_t>(std::ceil((4092.0 - truth.code_phase_chips) / chips_per_sample));
  }
  /// Code phase at sample n (unwrapped from the truth's at sample 0).
  double chips_at(std::size_t n) const { return truth.code_phase_chips + static_cast<double>(n) * chips_per_sample; }
  /// The GST code period (4 ms, counted from the week start) that starts at sample n0, from the
  /// pseudorange: t_sv = t_rcv - P / c on the receiver's GPS-labelled scale.
  std::int64_t period_at(std::size_t n) const {
    const double t_s = static_cast<double>(n) / sc.sample_rate_hz;
    const double p_m = truth.pseudorange_m - truth.doppler_hz * gps::kSpeedOfLight_mps / gps::kL1_Hz * t_s;
    return std::llround((sc.start_time.sow + t_s - p_m / gps::kSpeedOfLight_mps) * 250.0);
  }

  /// Correlation of samples [n, n + count) with `code` on BOC(1,1) starting at chip `chip`.
  std::complex<double> correlate(const galileo::E1CodeChips& code, std::size_t n, std::size_t count,
                                 double chip) const {
    const std::vector<float> replica =
        galileo::e1_replica(code, galileo::E1Subcarrier::kBoc11, chip, chips_per_sample, count);
    std::complex<double> sum = 0.0;
    for (std::size_t k = 0; k < count; ++k) sum += std::complex<double>(samples[n + k]) * double(replica[k]);
    return sum;
  }
};

TEST(GalileoSynthesis, E1SignalCorrelatesAtTheTruthCodePhaseAndDoppler) {
  const GalileoCapture cap(0.25);
  const int prn = cap.sat.prn;
  // A period 200 ms in, once the AGC has settled.
  const std::size_t n0 =
      cap.first_period_sample() + static_cast<std::size_t>(std::llround(50 * 4092.0 / cap.chips_per_sample));
  const std::size_t count = static_cast<std::size_t>(4092.0 / cap.chips_per_sample);
  const double chip0 = cap.chips_at(n0) - 51 * 4092.0;  // just past the period start
  // Code phase: the peak of E1-B and of E1-C within 0.1 chip of the truth.
  for (const galileo::E1CodeChips* code : {&galileo::e1b_code_chips(prn), &galileo::e1c_code_chips(prn)}) {
    double best_offset = 99.0, best = 0.0;
    for (double offset = -2.0; offset <= 2.0001; offset += 0.05) {
      const double m = std::abs(cap.correlate(*code, n0, count, chip0 + offset));
      if (m > best) {
        best = m;
        best_offset = offset;
      }
    }
    EXPECT_LE(std::abs(best_offset), 0.1);
    // Against the noise floor: the mean magnitude away from the peak (some 14 dB below it at
    // 47 dB-Hz over 4 ms).
    double off_peak = 0.0;
    for (int j = 1; j <= 20; ++j) off_peak += std::abs(cap.correlate(*code, n0, count, chip0 + 190.3 * j)) / 20.0;
    EXPECT_GT(best, 6.0 * off_peak);
  }
  // Doppler: wiping off a further offset lowers the correlation; the peak is at the truth.
  const std::vector<float> replica = galileo::e1_replica(galileo::e1c_code_chips(prn), galileo::E1Subcarrier::kBoc11,
                                                         chip0, cap.chips_per_sample, count);
  double best_hz = 99999.0, best = 0.0;
  for (double df = -600.0; df <= 600.0; df += 50.0) {
    std::complex<double> sum = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const double t = static_cast<double>(k) / cap.sc.sample_rate_hz;
      sum += std::complex<double>(cap.samples[n0 + k]) * double(replica[k]) * std::polar(1.0, -2.0 * M_PI * df * t);
    }
    if (std::abs(sum) > best) {
      best = std::abs(sum);
      best_hz = df;
    }
  }
  EXPECT_LE(std::abs(best_hz), 50.0);
}

TEST(GalileoSynthesis, PilotCarriesTheSecondaryCodeAlignedToGst) {
  const GalileoCapture cap(0.3);
  const int prn = cap.sat.prn;
  const std::size_t n0 = cap.first_period_sample();
  const std::int64_t period0 = cap.period_at(n0);
  const auto& secondary = galileo::e1c_secondary_chips();
  // 25 periods of the pilot, coherently, against the secondary code at each alignment.
  std::vector<std::complex<double>> per_period;
  for (int k = 0; k < 25; ++k) {
    const std::size_t n = n0 + static_cast<std::size_t>(std::llround(k * 4092.0 / cap.chips_per_sample));
    const std::size_t next = n0 + static_cast<std::size_t>(std::llround((k + 1) * 4092.0 / cap.chips_per_sample));
    per_period.push_back(cap.correlate(galileo::e1c_code_chips(prn), n, next - n, cap.chips_at(n) - 4092.0 * (k + 1)));
  }
  std::vector<double> by_shift;
  for (int shift = 0; shift < 25; ++shift) {
    std::complex<double> sum = 0.0;
    for (int k = 0; k < 25; ++k) sum += per_period[k] * double(secondary[(period0 + k + shift) % 25]);
    by_shift.push_back(std::abs(sum));
  }
  for (int shift = 1; shift < 25; ++shift) EXPECT_GT(by_shift[0], 3.0 * by_shift[shift]) << "shift " << shift;
}

TEST(GalileoSynthesis, InavSymbolsDecodeIntoTheEphemerisWords) {
  const GalileoCapture cap(4.7);
  const int prn = cap.sat.prn;
  const std::size_t n0 = cap.first_period_sample();
  const std::int64_t period0 = cap.period_at(n0);
  const auto& secondary = galileo::e1c_secondary_chips();
  // One soft symbol per code period: E1-B against the pilot (E1-C with its secondary chip),
  // whose sign in the composite signal is opposite.
  std::vector<float> soft;
  for (int k = 0;; ++k) {
    const std::size_t n = n0 + static_cast<std::size_t>(std::llround(k * 4092.0 / cap.chips_per_sample));
    const std::size_t next = n0 + static_cast<std::size_t>(std::llround((k + 1) * 4092.0 / cap.chips_per_sample));
    if (next > cap.samples.size()) break;
    const double chip = cap.chips_at(n) - 4092.0 * (k + 1);
    const std::complex<double> b = cap.correlate(galileo::e1b_code_chips(prn), n, next - n, chip);
    const std::complex<double> c =
        cap.correlate(galileo::e1c_code_chips(prn), n, next - n, chip) * double(secondary[(period0 + k) % 25]);
    soft.push_back(static_cast<float>(-(b * std::conj(c)).real()));
  }
  const galileo::GalileoEphemeris* eph =
      select_galileo_ephemeris(cap.nav, prn, galileo::gst_from_gps_time(cap.sc.start_time));
  ASSERT_NE(eph, nullptr);
  galileo::GalileoEphemeris decoded;
  int pages = 0, ephemeris_words = 0;
  for (std::size_t k = 0; k + 500 <= soft.size(); ++k) {
    if ((period0 + static_cast<std::int64_t>(k)) % 500 != 0) continue;  // an even GST second: a page starts
    // The sync pattern first: logic 0101100000 as levels.
    for (int i = 0; i < inav::kSyncSymbols; ++i)
      EXPECT_EQ(soft[k + i] > 0, inav::kSyncPattern[static_cast<std::size_t>(i)] == 0) << "sync symbol " << i;
    inav::PagePartSoftSymbols even{}, odd{};
    for (int i = 0; i < inav::kPagePartSymbols; ++i) {
      even[static_cast<std::size_t>(i)] = soft[k + 10 + static_cast<std::size_t>(i)];
      odd[static_cast<std::size_t>(i)] = soft[k + 260 + static_cast<std::size_t>(i)];
    }
    const inav::DecodedPage page = inav::decode_page(even, odd);
    EXPECT_TRUE(page.crc_ok);
    EXPECT_TRUE(page.parts_in_order);
    const std::int64_t page_start_s = (period0 + static_cast<std::int64_t>(k)) / 250;
    EXPECT_EQ(page.page.word, synthesized_inav_word(cap.nav, *eph, page_start_s));
    const int type = inav::word_type(page.page.word);
    if (type >= 1 && type <= 4) {
      EXPECT_EQ(inav::decode_ephemeris_word(page.page.word, decoded), eph->iod_nav);
      ++ephemeris_words;
    }
    ++pages;
  }
  EXPECT_GE(pages, 2);
  ASSERT_GE(ephemeris_words, 2);  // 20:30:00 and :02 GST: words 2 and 4
  EXPECT_NEAR(decoded.orbit.omega0_rad, std::remainder(eph->orbit.omega0_rad, 2 * galileo::kPi), 1e-8);
  EXPECT_NEAR(decoded.orbit.i0_rad, eph->orbit.i0_rad, 1e-8);
  EXPECT_NEAR(decoded.orbit.omega_rad, std::remainder(eph->orbit.omega_rad, 2 * galileo::kPi), 1e-8);
  EXPECT_NEAR(decoded.af0_s, eph->af0_s, 1e-10);
  EXPECT_NEAR(decoded.af1_sps, eph->af1_sps, 1e-13);
  EXPECT_EQ(decoded.prn, prn);
  EXPECT_EQ(decoded.toc_s, eph->toc_s);
}

}  // namespace
}  // namespace deepnav
