// The multipath channel in the synthesized samples: the `none` model changes nothing,
// the output does not depend on the thread count, and the echoes and the blockage are in
// the samples with the delay, amplitude and phase the channel gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "signals/ca_code.hpp"
#include "signals/gps_constants.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/multipath_channel.hpp"

namespace deepnav {
namespace {

const std::string kRoot = DEEPNAV_SOURCE_DIR;
constexpr double kPi = 3.14159265358979323846;
constexpr double kChip_m = gps::kSpeedOfLight_mps / gps::kCodeRate_cps;

std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("deepnav_multipath_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The bundled default scenario with extra YAML appended, shortened.
Scenario scenario_with(const std::string& extra_yaml, double duration_s) {
  const std::string path = kRoot + "/data/scenarios/default.yaml";
  Scenario sc = parse_scenario(read_text(path) + extra_yaml, path, kRoot + "/data/scenarios", kRoot);
  sc.duration_s = duration_s;
  sc.sample_rate_hz = 2.046e6;
  sc.max_satellites = 6;
  sc.sat_truth_rate_hz = 100;
  validate_scenario(sc);
  return sc;
}

std::vector<char> read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<char> synthesize(const Scenario& sc, const std::string& name, unsigned threads) {
  const auto dir = fresh_dir(name);
  SynthesisOptions opt;
  opt.threads = threads;
  IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir.string(), opt);
  return read_bytes(dir / if_file_name(sc.format));
}

struct Row {
  double t_s = 0, code_phase_chips = 0, doppler_hz = 0, carrier_phase_cycles = 0, elevation_deg = 0;
  double multipath_m = 0, los_gain_db = 0;
  int prn = 0, echoes = 0;
};

std::vector<Row> read_rows(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  EXPECT_NE(line.find(",antenna_gain_db,multipath_m,los_gain_db,echoes"), std::string::npos) << line;
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    Row r;
    double cn0, az, pr, range, rr, iono, tropo, clk, iono_model, tropo_model, orbit, clk_error, antenna;
    int on;
    s >> r.t_s >> r.prn >> r.code_phase_chips >> r.doppler_hz >> r.carrier_phase_cycles >> cn0 >> r.elevation_deg >>
        az >> pr >> range >> rr >> iono >> tropo >> clk >> on >> iono_model >> tropo_model >> orbit >> clk_error >>
        antenna >> r.multipath_m >> r.los_gain_db >> r.echoes;
    rows.push_back(r);
  }
  return rows;
}

/// Complex baseband samples (format gr_complex) of a synthesis run.
struct FloatRun {
  std::vector<char> raw;
  std::vector<Row> rows;
  const std::complex<float>* iq() const { return reinterpret_cast<const std::complex<float>*>(raw.data()); }
  std::int64_t size() const { return static_cast<std::int64_t>(raw.size() / sizeof(std::complex<float>)); }
};

FloatRun synthesize_float(const Scenario& sc, const std::string& name) {
  const auto dir = fresh_dir(name);
  SynthesisOptions opt;
  IfSynthesizer(sc, read_rinex_nav(sc.nav_file)).run(dir.string(), opt);
  return FloatRun{read_bytes(dir / if_file_name(sc.format)), read_rows(dir / "sat_truth.csv")};
}

/// Correlation over one code period, starting at the first period start of the code
/// delayed by `window_delay_chips`, of `x` (a difference of two runs, or a run) with
/// the satellite's code delayed by `replica_delay_chips` and the truth carrier.
std::complex<double> correlate(const Scenario& sc, const FloatRun& a, const FloatRun* minus, const Row& r,
                               double window_delay_chips, double replica_delay_chips) {
  const int n = static_cast<int>(sc.sample_rate_hz / 1000);
  const double fs = sc.sample_rate_hz;
  const auto k0 = static_cast<std::int64_t>(std::llround(r.t_s * 1000.0)) * n;
  const double rate = gps::kCodeRate_cps * (1.0 + r.doppler_hz / gps::kL1_Hz);
  const double phase0 = std::fmod(r.code_phase_chips - window_delay_chips + 1023.0, 1023.0);
  const int start = static_cast<int>(std::ceil((1023.0 - phase0) / rate * fs));
  if (k0 + start + n >= a.size()) return 0.0;
  const auto& code = ca_code_chips(r.prn);
  std::complex<double> sum = 0.0;
  for (int k = start; k < start + n; ++k) {
    const double t = k / fs;
    const double chip = r.code_phase_chips - replica_delay_chips + t * rate;
    const int c = static_cast<int>(std::floor(chip - 1023.0 * std::floor(chip / 1023.0))) % 1023;
    // IF 0: the signal's phase is -carrier_phase_cycles (the truth column) + Doppler * t.
    const std::complex<double> wipe = std::polar(1.0, -2.0 * kPi * (-r.carrier_phase_cycles + r.doppler_hz * t));
    std::complex<double> x = a.iq()[k0 + k];
    if (minus != nullptr) x -= std::complex<double>(minus->iq()[k0 + k]);
    sum += x * wipe * static_cast<double>(code[c]);
  }
  return sum;
}

/// Float samples without AGC, so two runs of the same seed differ by exactly the added paths.
Scenario float_scenario(const std::string& multipath_yaml, double duration_s, int satellites) {
  Scenario sc = scenario_with(multipath_yaml, duration_s);
  sc.sample_rate_hz = 5e6;  // not a multiple of the chip rate: the sampled correlation is a smooth triangle
  sc.format = SampleFormat::gr_complex;
  sc.adc.bits = 0;
  sc.adc.agc = false;
  sc.cn0 = Cn0Spec{};
  sc.cn0.fixed_dbhz = 80.0;  // thermal noise 0.2 % (1 sigma) of the prompt per millisecond
  sc.max_satellites = satellites;
  sc.sat_truth_rate_hz = 1000;
  validate_scenario(sc);
  return sc;
}

TEST(MultipathSynthesis, NoneSectionGivesTheSameSamplesAsNoSection) {
  const Scenario plain = scenario_with("", 0.15);
  const Scenario none = scenario_with("errors:\n  multipath: {model: none}\n", 0.15);
  EXPECT_EQ(synthesize(plain, "plain", 1), synthesize(none, "none", 1));
}

TEST(MultipathSynthesis, OutputIsIndependentOfThreadCount) {
  for (const char* env : {"open-sky", "urban"}) {
    const Scenario sc = scenario_with(std::string("errors:\n  multipath: ") + env + "\n", 0.25);
    const auto a = fresh_dir(std::string("t1_") + env), b = fresh_dir(std::string("t2_") + env);
    SynthesisOptions one, two;
    one.threads = 1;
    two.threads = 2;
    const NavData nav = read_rinex_nav(sc.nav_file);
    IfSynthesizer(sc, nav).run(a.string(), one);
    IfSynthesizer(sc, nav).run(b.string(), two);
    const auto fa = read_bytes(a / if_file_name(sc.format));
    EXPECT_EQ(fa.size(), static_cast<std::size_t>(0.25 * sc.sample_rate_hz * 2));
    EXPECT_EQ(fa, read_bytes(b / if_file_name(sc.format))) << env;
    EXPECT_EQ(read_bytes(a / "sat_truth.csv"), read_bytes(b / "sat_truth.csv")) << env;
    // And the channel changes the samples.
    EXPECT_NE(fa, synthesize(scenario_with("", 0.25), std::string("plain_") + env, 2)) << env;
  }
}

TEST(MultipathSynthesis, GroundEchoIsInTheSamplesWithItsDelayAmplitudeAndPhase) {
  // A 60 m mast gives an echo near 0.75 chip for the highest satellite; no rejection, so its
  // amplitude is |Gamma| = 0.5. The difference of the runs with and without it is the echo alone.
  const Scenario direct = float_scenario("", 0.03, 1);
  const Scenario echo = float_scenario(
      "errors:\n  multipath: {model: ground, antenna_height_m: 60, reflection_coefficient: 0.5, "
      "below_horizon_gain_db: 0}\n",
      0.03, 1);
  const FloatRun a = synthesize_float(direct, "ground_direct"), b = synthesize_float(echo, "ground_echo");
  ASSERT_EQ(a.rows.size(), b.rows.size());
  int checked = 0;
  for (std::size_t i = 0; i + 2 < a.rows.size(); i += 5) {
    const Row& r = a.rows[i];
    EXPECT_EQ(r.echoes, 0);
    EXPECT_EQ(r.multipath_m, 0.0);
    const Row& rb = b.rows[i];
    EXPECT_EQ(rb.echoes, 1);
    EXPECT_EQ(rb.los_gain_db, 0.0);
    const double el = r.elevation_deg * kPi / 180.0;
    const PathSet p = ground_reflection_paths(echo.errors.multipath, el);
    const double tau = p.echoes[0].excess_delay_m / kChip_m;
    // (the truth file's elevation has 1e-4 degree steps: a few centimetres of error here)
    EXPECT_NEAR(rb.multipath_m, ideal_dll_multipath_error_chips(p, 0.5) * kChip_m, 0.1);
    const std::complex<double> d = correlate(echo, a, nullptr, r, tau, 0.0);
    const std::complex<double> e = correlate(echo, b, &a, r, tau, tau);
    if (d == 0.0) continue;
    const std::complex<double> ratio = e / d;
    EXPECT_NEAR(std::abs(ratio), 0.5, 0.01) << r.t_s;
    EXPECT_NEAR(std::remainder(std::arg(ratio) - p.echoes[0].carrier_phase_rad, 2.0 * kPi), 0.0, 0.02) << r.t_s;
    // The echo's correlation peak sits at its delay: early and late taps balance.
    const double early = std::abs(correlate(echo, b, &a, r, tau, tau - 0.25));
    const double late = std::abs(correlate(echo, b, &a, r, tau, tau + 0.25));
    EXPECT_NEAR(early / late, 1.0, 0.02) << r.t_s;
    EXPECT_NEAR(early / std::abs(e), 0.75, 0.02) << r.t_s;
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

TEST(MultipathSynthesis, BlockageScalesTheDirectSignal) {
  // Land-mobile without echoes, in short spells, on the lowest satellite alone (no other
  // satellite's cross-correlation in the correlations): the difference of the runs with and
  // without the channel is (g - 1) times the direct signal.
  const std::string yaml =
      "errors:\n  multipath: {model: land-mobile, echoes: 0, blocked_probability: 0.4, mean_blocked_s: 0.05, "
      "blocked_attenuation_db: 20}\n";
  Scenario direct = float_scenario("", 1.0, 12);
  const auto sats = IfSynthesizer(direct, read_rinex_nav(direct.nav_file)).satellites();
  direct.prns = {sats.back().prn};
  direct.max_satellites = 1;
  Scenario sc = float_scenario(yaml, 1.0, 1);
  sc.prns = direct.prns;
  const FloatRun a = synthesize_float(direct, "block_direct"), b = synthesize_float(sc, "block_mp");
  ASSERT_EQ(a.rows.size(), b.rows.size());
  int blocked = 0, clear = 0;
  for (std::size_t i = 0; i < a.rows.size(); i += 3) {
    const Row& r = a.rows[i];
    const Row& rb = b.rows[i];
    ASSERT_EQ(r.prn, rb.prn);
    EXPECT_EQ(rb.echoes, 0);
    // Skip rows where the state changes within the correlation window (up to 2 ms later).
    if (i + 2 >= b.rows.size() || b.rows[i + 1].los_gain_db != rb.los_gain_db ||
        b.rows[i + 2].los_gain_db != rb.los_gain_db)
      continue;
    const std::complex<double> d = correlate(sc, a, nullptr, r, 0.0, 0.0);
    if (d == 0.0) continue;
    const std::complex<double> ratio = correlate(sc, b, &a, r, 0.0, 0.0) / d;
    const double gain = std::pow(10.0, rb.los_gain_db / 20.0);
    EXPECT_NEAR(ratio.real(), gain - 1.0, 0.012) << r.t_s << " PRN " << r.prn;
    EXPECT_NEAR(ratio.imag(), 0.0, 0.012) << r.t_s << " PRN " << r.prn;
    (rb.los_gain_db < -1.0 ? blocked : clear) += 1;
  }
  std::printf("PRN %d: %d blocked and %d clear epochs checked\n", sc.prns[0], blocked, clear);
  EXPECT_GT(blocked, 20);
  EXPECT_GT(clear, 20);
}

}  // namespace
}  // namespace deepnav
