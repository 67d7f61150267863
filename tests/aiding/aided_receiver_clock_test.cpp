// The aided receiver's clock model against the synthesizer's receiver clock: the filter
// follows the scalar receiver's clock steps exactly, so with an oscillator model as quiet
// as the synthesized TCXO its clock bias stays on the truth instead of wandering off.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "aiding/aided_receiver.hpp"
#include "ins/imu_file.hpp"
#include "receiver/products/truth_file.hpp"
#include "receiver/sources/file_sample_source.hpp"
#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/if_synthesizer.hpp"
#include "signals/sim/scenario.hpp"

namespace deepnav::aiding {
namespace {

TEST(AidedReceiverClock, UltraTightClockFollowsTheReceiverClockStepsWithoutDrifting) {
  Scenario sc =
      load_scenario(std::string(DEEPNAV_SOURCE_DIR) + "/data/scenarios/land_circle_aided_90s.yaml", DEEPNAV_SOURCE_DIR);
  sc.duration_s = 40.0;
  // A folder of this process's own: suites of several checkouts may run at once.
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("deepnav_aided_clock_test_" + std::to_string(::getpid()))).string();
  const NavData nav = read_rinex_nav(sc.nav_file);
  const SynthesisSummary synth = IfSynthesizer(sc, nav).run(dir, SynthesisOptions{});

  FileSampleSourceOptions so;
  so.path = synth.if_path;
  so.format = sc.format;
  so.sample_rate_hz = sc.sample_rate_hz;
  so.intermediate_frequency_hz = sc.if_hz;
  FileSampleSource source(so);
  AidedReceiverConfig cfg;
  cfg.mode = NavMode::ultra;
  cfg.receiver.reference_week = sc.start_time.week;
  cfg.imu = load_imu_grade(sc.imu.grades_file, sc.imu.grade).model;
  cfg.lever_arm_imu_to_antenna_b_m =
      -Eigen::Vector3d(sc.imu.lever_arm_m[0], sc.imu.lever_arm_m[1], sc.imu.lever_arm_m[2]);
  // The synthesized TCXO's own white frequency noise: a clock model this stiff cannot hide
  // a drift of the filter's own making.
  cfg.oscillator.h0 = 2e-21;
  AidedReceiver rx(cfg, source, read_imu_csv(synth.imu_path), sc.duration_s);
  rx.receiver().set_assisted_iono(nav.iono);
  rx.receiver().set_assisted_ephemerides(nav);
  const TruthFile truth(synth.truth_path);

  std::vector<std::pair<double, double>> clock_error_m;  // (t, filter bias minus true bias)
  rx.run([&](const AidedEpoch& a) {
    if (a.mode != NavMode::ultra || !a.valid || !a.receiver.t_rx || a.receiver.t_s >= sc.duration_s - 0.5) return;
    const std::optional<TruthSample> t = truth.at(a.receiver.t_s);
    ASSERT_TRUE(t && t->true_sow) << "truth.csv carries the receiver clock";
    const double true_bias_m = gps::kSpeedOfLight_mps * (a.receiver.t_rx->sow - *t->true_sow);
    clock_error_m.emplace_back(a.receiver.t_s, a.clock_bias_m - true_bias_m);
  });
  std::filesystem::remove_all(dir);

  // From t = 25 s (ten seconds into the ultra-tight run) to the end, across the receiver's
  // clock step at about 37 s: the error stays within the pseudorange noise. Following the
  // steps by differencing rounded receiver times made it wander off at 0.1 m/s here.
  std::size_t from = 0;
  while (from < clock_error_m.size() && clock_error_m[from].first < 25.0) ++from;
  ASSERT_GT(clock_error_m.size(), from + 10);
  double worst = 0.0;
  for (std::size_t i = from; i < clock_error_m.size(); ++i)
    worst = std::max(worst, std::abs(clock_error_m[i].second - clock_error_m[from].second));
  EXPECT_LT(worst, 0.6) << "from t = " << clock_error_m[from].first << " s to " << clock_error_m.back().first << " s";
}

}  // namespace
}  // namespace deepnav::aiding
