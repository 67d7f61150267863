#include "signals/if_synthesizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"

namespace deepnav {
namespace {

const std::string kRoot = DEEPNAV_SOURCE_DIR;

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("deepnav_synth_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

Scenario short_scenario(double duration_s, SampleFormat format, int bits) {
  Scenario sc = load_scenario(kRoot + "/data/scenarios/default.yaml", kRoot);
  sc.duration_s = duration_s;
  sc.sample_rate_hz = 2.046e6;
  sc.format = format;
  sc.adc.bits = bits;
  sc.max_satellites = 6;
  sc.truth_rate_hz = 100;
  sc.sat_truth_rate_hz = 100;
  validate_scenario(sc);
  return sc;
}

std::vector<char> read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct SatTruthRow {
  double t_s, code_phase_chips, doppler_hz, cn0_dbhz, pseudorange_m, range_m, iono_m, tropo_m, sat_clock_m;
  int prn, transmitting;
};

std::vector<SatTruthRow> read_sat_truth(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<SatTruthRow> rows;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    SatTruthRow r{};
    double carrier, el, az, rr;
    s >> r.t_s >> r.prn >> r.code_phase_chips >> r.doppler_hz >> carrier >> r.cn0_dbhz >> el >> az >> r.pseudorange_m >>
        r.range_m >> rr >> r.iono_m >> r.tropo_m >> r.sat_clock_m >> r.transmitting;
    rows.push_back(r);
  }
  return rows;
}

TEST(IfSynthesizer, OutputIsIndependentOfThreadCount) {
  const Scenario sc = short_scenario(0.25, SampleFormat::ibyte, 2);
  const NavData nav = read_rinex_nav(sc.nav_file);
  const auto a = fresh_dir("threads1"), b = fresh_dir("threads3");
  SynthesisOptions one;
  one.threads = 1;
  SynthesisOptions three;
  three.threads = 3;
  IfSynthesizer(sc, nav).run(a.string(), one);
  IfSynthesizer(sc, nav).run(b.string(), three);
  const auto fa = read_bytes(a / if_file_name(sc.format));
  EXPECT_EQ(fa.size(), static_cast<std::size_t>(0.25 * sc.sample_rate_hz * 2));
  EXPECT_EQ(fa, read_bytes(b / if_file_name(sc.format)));
  EXPECT_EQ(read_bytes(a / "sat_truth.csv"), read_bytes(b / "sat_truth.csv"));
}

TEST(IfSynthesizer, SignalMatchesTruthCodePhaseDopplerAndPower) {
  // Float output (no quantization): correlate each satellite with a replica built from
  // the per-satellite truth and measure C/N0 from the prompt power against the noise
  // power of a correlator with an absent PRN's code.
  Scenario sc = short_scenario(0.2, SampleFormat::gr_complex, 0);
  sc.cn0 = Cn0Spec{};
  sc.cn0.fixed_dbhz = 45.0;
  sc.sat_truth_rate_hz = 1000;
  const NavData nav = read_rinex_nav(sc.nav_file);
  const auto dir = fresh_dir("truth");
  SynthesisOptions opt;
  const SynthesisSummary summary = IfSynthesizer(sc, nav).run(dir.string(), opt);
  ASSERT_GE(summary.satellites.size(), 4u);
  const auto raw = read_bytes(dir / if_file_name(sc.format));
  const auto* iq = reinterpret_cast<const std::complex<float>*>(raw.data());
  const auto rows = read_sat_truth(dir / "sat_truth.csv");
  const int n = static_cast<int>(sc.sample_rate_hz / 1000);
  std::set<int> present;
  for (const auto& s : summary.satellites) present.insert(s.prn);
  std::vector<int> absent;
  for (int prn = 1; absent.size() < 4; ++prn)
    if (!present.count(prn)) absent.push_back(prn);
  const std::int64_t total = static_cast<std::int64_t>(raw.size() / sizeof(std::complex<float>));

  std::vector<double> signal_power, absent_power;
  for (const auto& sat : summary.satellites) {
    double signal = 0.0, noise = 0.0;
    int epochs = 0;
    for (const auto& r : rows) {
      if (r.prn != sat.prn) continue;
      const auto k0 = static_cast<std::int64_t>(std::llround(r.t_s * 1000.0)) * n;
      const double code_rate = gps::kCodeRate_cps * (1.0 + r.doppler_hz / gps::kL1_Hz);
      // Integrate over one whole code period (so no data-bit edge falls inside).
      const int start = static_cast<int>(std::ceil((1023.0 - r.code_phase_chips) / code_rate * sc.sample_rate_hz));
      if (k0 + start + n >= total) continue;
      std::complex<double> prompt = 0.0;
      std::vector<std::complex<double>> others(absent.size(), 0.0);
      for (int k = start; k < start + n; ++k) {
        const double t = k / sc.sample_rate_hz;
        const int chip = static_cast<int>(std::floor(r.code_phase_chips + t * code_rate)) % 1023;
        const std::complex<double> wipe = std::polar(1.0, -2.0 * M_PI * r.doppler_hz * t);
        const std::complex<double> x = std::complex<double>(iq[k0 + k]) * wipe;
        prompt += x * static_cast<double>(ca_code_chips(sat.prn)[chip]);
        for (std::size_t a = 0; a < absent.size(); ++a) others[a] += x * static_cast<double>(ca_code_chips(absent[a])[chip]);
      }
      signal += std::norm(prompt);
      for (const auto& o : others) noise += std::norm(o) / static_cast<double>(absent.size());
      ++epochs;
    }
    ASSERT_GT(epochs, 150);
    signal_power.push_back(signal / epochs);
    absent_power.push_back(noise / epochs);
  }
  // Prompt power: |A n|^2 + n N0 fs + cross-correlation with the other satellites; an
  // absent PRN's correlator: n N0 fs + cross-correlation with every satellite, each about
  // |A n|^2 / 1023 (Gold code cross-correlation averaged over code phase and Doppler).
  // So |A n|^2 ~ prompt - absent, and n N0 fs ~ absent - sum(|A n|^2) / 1023. The file's
  // scale is the AGC's, so C/N0 comes from this ratio: C/N0 = |A n|^2 / (n N0 fs) * fs / n.
  double cross = 0.0, thermal = 0.0;
  for (std::size_t i = 0; i < signal_power.size(); ++i) {
    cross += (signal_power[i] - absent_power[i]) / 1023.0;
    thermal += absent_power[i] / static_cast<double>(signal_power.size());
  }
  thermal -= cross;
  for (std::size_t i = 0; i < signal_power.size(); ++i) {
    const double cn0 = 10.0 * std::log10((signal_power[i] - absent_power[i]) / thermal * sc.sample_rate_hz / n);
    EXPECT_NEAR(cn0, 45.0, 0.5) << "PRN " << summary.satellites[i].prn;
  }
}

TEST(IfSynthesizer, TruthPseudorangesAreConsistent) {
  Scenario sc = short_scenario(0.1, SampleFormat::ibyte, 2);
  sc.outages.push_back(OutageSpec{0.05, 0.08, {}});
  const NavData nav = read_rinex_nav(sc.nav_file);
  const auto dir = fresh_dir("consistency");
  SynthesisOptions opt;
  IfSynthesizer(sc, nav).run(dir.string(), opt);
  int rows_in_outage = 0;
  for (const auto& r : read_sat_truth(dir / "sat_truth.csv")) {
    EXPECT_NEAR(r.pseudorange_m - (r.range_m + gps::kSpeedOfLight_mps * 1.5e-4 - r.sat_clock_m + r.iono_m + r.tropo_m),
                0.0, gps::kSpeedOfLight_mps * 1e-6)  // clock drift of 0.5 ppm over 0.1 s
        << r.prn << " " << r.t_s;
    EXPECT_GT(r.iono_m, 0.3);
    EXPECT_GT(r.tropo_m, 2.0);
    const bool outage = r.t_s >= 0.05 - 1e-9 && r.t_s < 0.08 - 1e-9;
    EXPECT_EQ(r.transmitting, outage ? 0 : 1) << r.t_s;
    rows_in_outage += outage;
  }
  EXPECT_GT(rows_in_outage, 0);
  std::ifstream truth(dir / "truth.csv");
  std::string line;
  int lines = 0;
  while (std::getline(truth, line)) ++lines;
  EXPECT_EQ(lines, 1 + 10);  // header + 100 Hz over 0.1 s
  EXPECT_TRUE(std::filesystem::exists(dir / "scenario.yaml"));
}

TEST(IfSynthesizer, UnwritableOutputFolderIsAnErrorAndLeavesNothing) {
  const Scenario sc = short_scenario(0.01, SampleFormat::ibyte, 2);
  const NavData nav = read_rinex_nav(sc.nav_file);
  const auto blocker = fresh_dir("blocker");
  std::ofstream(blocker.string()) << "a file where a folder should be";
  SynthesisOptions opt;
  EXPECT_THROW(IfSynthesizer(sc, nav).run((blocker / "out").string(), opt), std::runtime_error);
  std::filesystem::remove(blocker);
}

}  // namespace
}  // namespace deepnav
