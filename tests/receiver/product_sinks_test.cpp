// The file products as sinks: they write as the run goes, under `<name>.<pid>.partial`, and
// take their final names only at finish(); the streamed files equal the whole-run
// writers' output, and RINEX observations before the first fix wait for its position.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "receiver/products/file_products.hpp"
#include "receiver/products/rinex_obs_writer.hpp"
#include "receiver/products/track_writers.hpp"

namespace deepnav {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

ReceiverEpoch epoch_at(double t_s, bool with_fix) {
  ReceiverEpoch e;
  e.t_s = t_s;
  e.t_rx = GpsTime{2190, 525600.0 + t_s};
  e.observations.push_back({7, 21000000.0 + t_s, -1234.5, 1000.25 + t_s, 45.5, 10.0});
  e.pvt.valid = with_fix;
  if (with_fix) {
    e.pvt.t = *e.t_rx;
    e.pvt.llh = {37.5 * M_PI / 180, 127.0 * M_PI / 180, 50.0 + t_s};
    e.pvt.r_ecef_m = wgs84::llh_to_ecef(e.pvt.llh);
    for (int prn : {7, 10, 12, 23}) e.pvt.used_satellites.push_back({GnssSystem::gps, prn});
  }
  return e;
}

/// Where this process writes `name` until it is complete (ins/output_file.hpp).
std::string partial_of(const std::string& name) { return name + "." + std::to_string(::getpid()) + ".partial"; }

class ProductSinks : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test and process: ctest runs the tests as parallel processes.
    dir_ = fs::temp_directory_path() /
           ("deepnav_sinks_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ProductSinks, FilesAppearOnlyWhenFinishedAndEqualTheWholeRunWriters) {
  auto sinks = file_products(dir_.string(), "run", 1.0);
  std::vector<ReceiverEpoch> epochs;
  std::vector<PvtSolution> fixes;
  for (int k = 0; k < 5; ++k) {
    epochs.push_back(epoch_at(k, k >= 2));  // fixes from the third epoch on
    if (epochs.back().pvt.valid) fixes.push_back(epochs.back().pvt);
    const NavigationEpoch e{epochs.back(), epochs.back().pvt, false, "scalar", 4, 4, 18};
    for (auto& s : sinks) s->on_epoch(e);
  }
  for (const char* name : {"pvt.csv", "obs.rnx", "track.kml", "fixes.nmea"}) {
    EXPECT_FALSE(fs::exists(dir_ / name)) << name << " exists before the run ended";
    EXPECT_TRUE(fs::exists(dir_ / partial_of(name))) << name;
  }
  for (auto& s : sinks) s->finish(NavData{});
  RinexObsHeader header;
  header.approx_position_ecef_m = fixes.front().r_ecef_m;
  EXPECT_EQ(read_file(dir_ / "obs.rnx"), rinex3_observation_file(header, epochs));
  EXPECT_EQ(read_file(dir_ / "track.kml"), kml_track(fixes, "run"));
  EXPECT_EQ(read_file(dir_ / "track.gpx"), gpx_track(fixes, "run", 18));
  std::ifstream pvt(dir_ / "pvt.csv");
  int lines = 0;
  for (std::string line; std::getline(pvt, line);) ++lines;
  EXPECT_EQ(lines, 1 + 3);  // header and one row per fix
  EXPECT_FALSE(fs::exists(dir_ / partial_of("pvt.csv")));
}

TEST_F(ProductSinks, WriteAsTheRunGoes) {
  TrackSink sink((dir_ / "track.kml").string(), (dir_ / "track.gpx").string(), "run");
  std::vector<PvtSolution> fixes;
  for (int k = 0; k < 2000; ++k) {
    const ReceiverEpoch ep = epoch_at(k, true);
    sink.on_epoch({ep, ep.pvt, false, "scalar", 4, 4, 18});
    fixes.push_back(ep.pvt);
  }
  // Beyond the stream's buffer, the points are on disk before the run ends (not held).
  const std::string so_far = read_file(dir_ / partial_of("track.kml"));
  EXPECT_GT(so_far.size(), kml_track(fixes, "run").size() / 2);
  EXPECT_EQ(so_far, kml_track(fixes, "run").substr(0, so_far.size()));
}

TEST_F(ProductSinks, UnfinishedRunLeavesNoFile) {
  {
    auto sinks = file_products(dir_.string(), "run", 1.0);
    const ReceiverEpoch ep = epoch_at(0, true);
    for (auto& s : sinks) s->on_epoch({ep, ep.pvt, false, "scalar", 4, 4, 18});
  }  // the run failed: nothing finished
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(ProductSinks, RinexWithoutAnyFixStillHasItsEpochs) {
  RinexObsSink sink((dir_ / "obs.rnx").string(), 1.0);
  std::vector<ReceiverEpoch> epochs{epoch_at(0, false), epoch_at(1, false)};
  for (const auto& ep : epochs) sink.on_epoch({ep, ep.pvt, false, "scalar", 0, 0, 18});
  sink.finish(NavData{});
  EXPECT_EQ(read_file(dir_ / "obs.rnx"), rinex3_observation_file(RinexObsHeader{}, epochs));
}

}  // namespace
}  // namespace deepnav
