#include "signals/sim/if_synthesizer.hpp"

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
        for (std::size_t a = 0; a < absent.size(); ++a)
          others[a] += x * static_cast<double>(ca_code_chips(absent[a])[chip]);
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
  sc.outages.push_back(OutageSpec{0.05, 0.08, {}, {}});
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

/// sat_truth.csv as columns by header name.
std::map<std::string, std::vector<double>> read_columns(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (std::size_t i = 0; i < names.size() && std::getline(row, cell, ','); ++i)
      cols[names[i]].push_back(std::stod(cell));
  }
  return cols;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// short_scenario with the default scenario's text plus `extra` YAML.
Scenario short_scenario_with(const std::string& extra, double duration_s) {
  const std::string path = kRoot + "/data/scenarios/default.yaml";
  Scenario sc = parse_scenario(read_text(path) + extra, path, kRoot + "/data/scenarios", kRoot);
  const Scenario plain = short_scenario(duration_s, SampleFormat::ibyte, 2);
  sc.duration_s = plain.duration_s;
  sc.sample_rate_hz = plain.sample_rate_hz;
  sc.format = plain.format;
  sc.adc = plain.adc;
  sc.max_satellites = plain.max_satellites;
  sc.truth_rate_hz = plain.truth_rate_hz;
  sc.sat_truth_rate_hz = plain.sat_truth_rate_hz;
  validate_scenario(sc);
  return sc;
}

TEST(IfSynthesizer, ErrorPresetNoneIsTheScenarioWithoutErrors) {
  const Scenario without = short_scenario(0.15, SampleFormat::ibyte, 2);
  const Scenario with_none = short_scenario_with("errors: {preset: none}\n", 0.15);
  ASSERT_EQ(without.errors, with_none.errors);
  const NavData nav = read_rinex_nav(without.nav_file);
  const auto a = fresh_dir("errors_absent"), b = fresh_dir("errors_none");
  SynthesisOptions opt;
  IfSynthesizer(without, nav).run(a.string(), opt);
  IfSynthesizer(with_none, nav).run(b.string(), opt);
  EXPECT_EQ(read_bytes(a / if_file_name(without.format)), read_bytes(b / if_file_name(without.format)));
  EXPECT_EQ(read_bytes(a / "truth.csv"), read_bytes(b / "truth.csv"));
  EXPECT_EQ(read_bytes(a / "sat_truth.csv"), read_bytes(b / "sat_truth.csv"));
  // Every error column says "no error": the receiver's models are the truth.
  auto cols = read_columns(b / "sat_truth.csv");
  ASSERT_GT(cols["prn"].size(), 10u);
  for (std::size_t i = 0; i < cols["prn"].size(); ++i) {
    EXPECT_EQ(cols["orbit_m"][i], 0.0);
    EXPECT_EQ(cols["sat_clock_error_m"][i], 0.0);
    EXPECT_EQ(cols["antenna_gain_db"][i], 0.0);
    EXPECT_EQ(cols["iono_broadcast_m"][i], cols["iono_m"][i]);
    EXPECT_EQ(cols["tropo_model_m"][i], cols["tropo_m"][i]);
  }
}

TEST(IfSynthesizer, OpenSkyErrorsAreInTheSignalAndTheTruth) {
  const Scenario sc = short_scenario_with("errors: {preset: open-sky}\n", 0.2);
  const NavData nav = read_rinex_nav(sc.nav_file);
  const auto a = fresh_dir("open_sky_1"), b = fresh_dir("open_sky_3"), plain = fresh_dir("open_sky_plain");
  SynthesisOptions one, three;
  three.threads = 3;
  IfSynthesizer(sc, nav).run(a.string(), one);
  IfSynthesizer(sc, nav).run(b.string(), three);
  // Whatever the thread count, the same bytes.
  const auto if_a = read_bytes(a / if_file_name(sc.format));
  EXPECT_EQ(if_a, read_bytes(b / if_file_name(sc.format)));
  EXPECT_EQ(read_bytes(a / "sat_truth.csv"), read_bytes(b / "sat_truth.csv"));
  // The world differs from the receiver's models, so the signal differs from preset none.
  IfSynthesizer(short_scenario(0.2, SampleFormat::ibyte, 2), nav).run(plain.string(), one);
  EXPECT_NE(if_a, read_bytes(plain / if_file_name(sc.format)));
  EXPECT_EQ(read_bytes(a / "truth.csv"), read_bytes(plain / "truth.csv"));  // the receiver did not move

  auto cols = read_columns(a / "sat_truth.csv");
  const std::size_t n = cols["prn"].size();
  ASSERT_GT(n, 10u);
  const double c = gps::kSpeedOfLight_mps;
  double orbit2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = cols["t_s"][i];
    // Pseudorange = broadcast range + orbit error + c b - (broadcast clock + clock error) + I + T.
    const double bias_m = c * (1.5e-4 + 0.5e-6 * t);
    EXPECT_NEAR(cols["pseudorange_m"][i] - (cols["range_m"][i] + cols["orbit_m"][i] + bias_m - cols["sat_clock_m"][i] -
                                            cols["sat_clock_error_m"][i] + cols["iono_m"][i] + cols["tropo_m"][i]),
                0.0, 0.01 + c * 2e-9);  // printed to 0.1 mm; the TCXO's noise over 0.2 s is below 2 ns
    EXPECT_NE(cols["iono_m"][i], cols["iono_broadcast_m"][i]);
    EXPECT_GT(cols["tropo_m"][i] - cols["tropo_model_m"][i], 0.03);  // humid summer air
    EXPECT_LT(cols["antenna_gain_db"][i], 0.0);
    EXPECT_GT(cols["antenna_gain_db"][i], -6.0);  // satellites above the 10 deg mask
    EXPECT_NE(cols["sat_clock_error_m"][i], 0.0);
    orbit2 += cols["orbit_m"][i] * cols["orbit_m"][i];
  }
  EXPECT_GT(std::sqrt(orbit2 / static_cast<double>(n)), 0.05);
  EXPECT_LT(std::sqrt(orbit2 / static_cast<double>(n)), 1.5);
  // The antenna gain is in the C/N0 (elevation model 40..48 dB-Hz before it).
  auto plain_cols = read_columns(plain / "sat_truth.csv");
  for (std::size_t i = 0; i < n; ++i)
    EXPECT_NEAR(cols["cn0_dbhz"][i], plain_cols["cn0_dbhz"][i] + cols["antenna_gain_db"][i], 0.011);

  // Another seed: other orbit, clock and atmosphere errors.
  Scenario other = sc;
  other.seed = 2;
  const auto d = fresh_dir("open_sky_seed2");
  IfSynthesizer(other, nav).run(d.string(), one);
  auto other_cols = read_columns(d / "sat_truth.csv");
  EXPECT_NE(other_cols["orbit_m"], cols["orbit_m"]);
  EXPECT_NE(other_cols["sat_clock_error_m"], cols["sat_clock_error_m"]);
  EXPECT_NE(other_cols["iono_m"], cols["iono_m"]);
  EXPECT_EQ(other_cols["iono_broadcast_m"], cols["iono_broadcast_m"]);
}

TEST(IfSynthesizer, AtmosphereSwitchesStillRemoveTheTrueDelay) {
  Scenario sc = short_scenario_with("errors: {preset: open-sky}\n", 0.05);
  sc.ionosphere = false;
  sc.troposphere = false;
  const auto dir = fresh_dir("open_sky_no_atmosphere");
  IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir.string(), SynthesisOptions{});
  auto cols = read_columns(dir / "sat_truth.csv");
  ASSERT_GT(cols["prn"].size(), 4u);
  for (std::size_t i = 0; i < cols["prn"].size(); ++i) {
    EXPECT_EQ(cols["iono_m"][i], 0.0);
    EXPECT_EQ(cols["tropo_m"][i], 0.0);
    EXPECT_GT(cols["iono_broadcast_m"][i], 0.3);  // what the receiver will still remove
    EXPECT_GT(cols["tropo_model_m"][i], 2.0);
  }
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

TEST(IfSynthesizer, AbsurdRangeRateIsAnErrorNamingTheSatellite) {
  // An orbit no navigation file reader would pass (delta n = 1.23e19 rad/s, as in a corrupt
  // file): the synthesizer stops with the PRN and time instead of spinning in the code fill.
  const Scenario sc = short_scenario(0.01, SampleFormat::ibyte, 4);
  NavData nav = read_rinex_nav(sc.nav_file);
  for (Ephemeris& e : nav.ephemerides) e.delta_n_radps = 1.23456789012e19;
  const auto dir = fresh_dir("absurd");
  try {
    IfSynthesizer(sc, nav).run(dir.string(), SynthesisOptions{});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("synthesizer: PRN "), std::string::npos) << m;
    EXPECT_NE(m.find("at t = 0.000 s: the signal implies a range rate of"), std::string::npos) << m;
    EXPECT_NE(m.find("brdc0010.22n, PRN "), std::string::npos) << m;
  }
  for (int threads : {1, 3}) {  // an error inside a worker thread too
    SynthesisOptions o;
    o.threads = static_cast<unsigned>(threads);
    EXPECT_THROW(IfSynthesizer(sc, nav).run(fresh_dir("absurd_threads").string(), o), std::runtime_error);
  }
}

}  // namespace
}  // namespace deepnav
