#include <gtest/gtest.h>

#include <cmath>

#include "receiver/products/nmea_writer.hpp"
#include "receiver/products/rinex_obs_writer.hpp"
#include "receiver/products/track_writers.hpp"

namespace deepnav {
namespace {

PvtSolution sample_fix() {
  PvtSolution p;
  p.valid = true;
  p.t = GpsTime{2190, 525618.0};
  p.llh = {37.5665 * M_PI / 180, 126.978 * M_PI / 180, 40.25};
  p.r_ecef_m = wgs84::llh_to_ecef(p.llh);
  for (int prn : {10, 23, 24, 12, 25}) {
    const SatelliteId sat{GnssSystem::gps, prn};
    p.used_satellites.push_back(sat);
    p.elevation_rad[sat] = 0.5;
    p.azimuth_rad[sat] = 1.0;
  }
  p.dops = {2.0, 1.8, 1.0, 1.5, 0.9};
  return p;
}

TEST(Nmea, ChecksumAndFields) {
  EXPECT_EQ(nmea_checksum("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"), "*47");
  const std::string s = nmea_sentences(sample_fix(), {{{GnssSystem::gps, 10}, 45.2}}, 18);
  // 2022-01-01 02:00:18 GPS = 02:00:00 UTC.
  EXPECT_NE(s.find("$GPGGA,020000.00,3733.99000,N,12658.68000,E,1,05,1.0,40.25,M"), std::string::npos) << s;
  EXPECT_NE(s.find("$GPRMC,020000.00,A,"), std::string::npos);
  EXPECT_NE(s.find(",010122,"), std::string::npos);
  EXPECT_NE(s.find("$GPGSA,A,3,10,23,24,12,25,"), std::string::npos);
  EXPECT_NE(s.find("$GPGSV,2,1,05,10,29,057,45"), std::string::npos) << s;
  // Every sentence carries its own valid checksum.
  std::size_t start = 0;
  int sentences = 0;
  while ((start = s.find('$', start)) != std::string::npos) {
    const auto star = s.find('*', start);
    EXPECT_EQ(s.substr(star, 3), nmea_checksum(s.substr(start + 1, star - start - 1)));
    start = star;
    ++sentences;
  }
  EXPECT_EQ(sentences, 5);
}

TEST(Nmea, AnInsCarriedSolutionIsWrittenAsDeadReckoning) {
  const std::string gnss = nmea_sentences(sample_fix(), {{{GnssSystem::gps, 10}, 45.2}}, 18);
  const std::string coast = nmea_sentences(sample_fix(), {{{GnssSystem::gps, 10}, 45.2}}, 18, true);
  EXPECT_NE(coast.find("$GPGGA,020000.00,3733.99000,N,12658.68000,E,6,05,"), std::string::npos) << coast;
  EXPECT_NE(coast.find(",010122,,,E*"), std::string::npos) << coast;
  EXPECT_NE(gnss.find(",010122,,,A*"), std::string::npos) << gnss;
}

TEST(Tracks, KmlAndGpxCarryEveryFix) {
  const std::vector<PvtSolution> fixes{sample_fix(), sample_fix()};
  const std::string kml = kml_track(fixes, "run");
  EXPECT_NE(kml.find("126.978000000,37.566500000,40.250"), std::string::npos);
  const std::string gpx = gpx_track(fixes, "run", 18);
  EXPECT_NE(
      gpx.find("<trkpt lat=\"37.566500000\" lon=\"126.978000000\"><ele>40.250</ele><time>2022-01-01T02:00:00.000Z"),
      std::string::npos)
      << gpx;
}

TEST(RinexObs, HeaderAndEpochLayout) {
  ReceiverEpoch e;
  e.t_rx = GpsTime{2190, 525618.5};
  e.observations.push_back({7, 21000000.1234, -1234.5, 1000.25, 45.5, 10.0});
  RinexObsHeader h;
  const std::string text = rinex3_observation_file(h, {e});
  EXPECT_NE(text.find("     3.04           OBSERVATION DATA    G (GPS)             RINEX VERSION / TYPE\n"),
            std::string::npos);
  EXPECT_NE(text.find("G    4 C1C L1C D1C S1C"), std::string::npos);
  EXPECT_NE(text.find("> 2022 01 01 02 00 18.5000000  0  1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("G07  21000000.123       -1000.250       -1234.500          45.500"), std::string::npos) << text;
  // Header lines are 80 columns wide with the label from column 61.
  const auto first_line = text.substr(0, text.find('\n'));
  EXPECT_EQ(first_line.size(), 80u);
}

}  // namespace
}  // namespace deepnav
