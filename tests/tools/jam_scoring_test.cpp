// The jamming benchmark's channel timeline on a mixed scenario's truth: satellites keyed by
// system and number, the systems the receiver did not track left out, Galileo channels
// judged by their observation epochs.
#include "tools/bench/jam_scoring.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/tools/deepnav_cli.hpp"

namespace deepnav::bench {
namespace {

using test::ScratchDir;

/// A sat_truth.csv of G05 and E05 over 0-10 s at 10 Hz, each with a constant Doppler.
std::string write_truth(const ScratchDir& dir) {
  const std::string path = dir / "sat_truth.csv";
  std::ofstream f(path);
  f << "t_s,prn,doppler_hz\n";
  for (int k = 0; k <= 100; ++k) f << 0.1 * k << ",G05,1000\n" << 0.1 * k << ",E05,-2000\n";
  return path;
}

TEST(JamChannelTimeline, KeysSatellitesBySystemAndLeavesOutUntrackedSystems) {
  const ScratchDir dir("jam_scoring_test");
  const std::string truth = write_truth(dir);
  std::vector<TrackingRow> rows;
  for (int k = 0; k < 100; ++k)  // G05: 100 ms integrations, on its Doppler
    rows.push_back({0.1 * k, {GnssSystem::gps, 5}, ChannelState::tracking, 0.1, 1000.0, 45.0, std::nullopt});
  for (int k = 0; k < 10; ++k)  // E05: one row per 1 s epoch, its Doppler 40 Hz off after 5 s
    rows.push_back({1.0 * k,
                    {GnssSystem::galileo, 5},
                    ChannelState::tracking,
                    1.0,
                    k < 5 ? -2000.0 : -1960.0,
                    44.0,
                    std::nullopt});

  const ChannelTimeline gps_only = channel_timeline(rows, truth, 2.0, 10.0);
  EXPECT_EQ(gps_only.satellites, (std::vector<SatelliteId>{{GnssSystem::gps, 5}}));
  const ChannelTimeline both = channel_timeline(rows, truth, 2.0, 10.0, {GnssSystem::gps, GnssSystem::galileo});
  ASSERT_EQ(both.satellites.size(), 2u);
  EXPECT_EQ(both.tracked_at(4.5), 2);
  EXPECT_EQ(both.tracked_at(8.5), 1) << "E05 follows another Doppler after 5 s";

  const JamChannels channels = channel_figures(both, 2.0, 10.0);
  ASSERT_EQ(channels.count("5"), 1u) << "a GPS satellite keyed by its PRN alone, as before";
  ASSERT_EQ(channels.count("E05"), 1u);
  EXPECT_NEAR(channels.at("5").tracked_fraction, 1.0, 1e-9);
  EXPECT_NEAR(channels.at("E05").tracked_fraction, 3.0 / 8.0, 1e-9);  // epochs starting 2, 3, 4 s
}

}  // namespace
}  // namespace deepnav::bench
