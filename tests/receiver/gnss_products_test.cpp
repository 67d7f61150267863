// Products of GPS + Galileo fixes: RINEX 3 mixed observation files written and read back,
// NMEA sentences with the GN / GA talkers, and a cross-check of the two-system fix against
// RTKLIB (rnx2rtkp -sys G,E) on a mixed observation file and a mixed navigation file.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "receiver/observations/rinex_obs_reader.hpp"
#include "receiver/products/nmea_writer.hpp"
#include "receiver/products/rinex_obs_writer.hpp"
#include "signals/galileo/galileo_constants.hpp"
#include "tests/receiver/gnss_scene.hpp"

namespace deepnav {
namespace {

namespace fs = std::filesystem;
using test::GnssScene;
using test::vacuum_solver;

const GnssScene& scene() {
  static const GnssScene s;
  return s;
}

/// Receiver epochs at 1 s steps from the scene's epoch with the observations of `systems`.
std::vector<ReceiverEpoch> receiver_epochs(const std::vector<GnssSystem>& systems, int count, double noise_m) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(17);
  std::vector<ReceiverEpoch> epochs;
  for (int k = 0; k < count; ++k) {
    ReceiverEpoch e;
    e.t_rx = s.t_rx.plus_seconds(k);
    std::vector<PseudorangeObservation> obs;
    for (const GnssSystem system : systems) {
      const auto more =
          system == GnssSystem::gps ? s.gps_obs(*e.t_rx, noise_m, rng) : s.galileo_obs(*e.t_rx, noise_m, rng);
      obs.insert(obs.end(), more.begin(), more.end());
    }
    for (const PseudorangeObservation& o : obs) {
      ChannelObservation c;
      c.prn = o.prn;
      c.system = o.system;
      c.pseudorange_m = o.pseudorange_m;
      c.doppler_hz = o.doppler_hz;
      c.carrier_phase_cycles = -1000.25 * (k + 1);
      c.cn0_dbhz = 44.0 + o.prn % 5;
      e.observations.push_back(c);
    }
    epochs.push_back(e);
  }
  return epochs;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// The fix of a read-back epoch: both systems' pseudoranges.
PvtSolution solve_read_epoch(PvtSolver& solver, const ObservationEpoch& e) {
  const GnssScene& s = scene();
  std::vector<PseudorangeObservation> obs;
  for (const auto& [system, list] : {std::pair{GnssSystem::gps, &e.gps}, std::pair{GnssSystem::galileo, &e.galileo}})
    for (const GpsL1Observation& o : *list) {
      PseudorangeObservation p;
      p.prn = o.prn;
      p.system = system;
      p.pseudorange_m = o.pseudorange_m.value_or(0.0);
      p.doppler_hz = o.doppler_hz.value_or(0.0);
      p.cn0_dbhz = o.cn0_dbhz.value_or(45.0);
      obs.push_back(p);
    }
  return solver.solve(e.t, obs, s.gps, s.galileo, s.gps_nav.iono);
}

TEST(GnssRinexObs, AMixedFileDeclaresBothSystemsAndReadsBack) {
  const std::vector<GnssSystem> both = {GnssSystem::gps, GnssSystem::galileo};
  const std::vector<ReceiverEpoch> epochs = receiver_epochs(both, 3, 0.0);
  RinexObsHeader h;
  h.systems = both;
  h.approx_position_ecef_m = scene().r_ecef_m;
  const std::string text = rinex3_observation_file(h, epochs);
  const std::vector<std::string> lines = lines_of(text);
  EXPECT_EQ(lines[0].substr(40, 20), "M (MIXED)           ");
  EXPECT_NE(text.find("G    4 C1C L1C D1C S1C"), std::string::npos);
  EXPECT_NE(text.find("E    4 C1C L1C D1C S1C"), std::string::npos);
  EXPECT_NE(text.find("  2022     1     1    23    50    0.0000000     GPS         TIME OF FIRST OBS"),
            std::string::npos);
  const std::string e_line = fmt::format("E{:02d}", scene().galileo.begin()->first);
  EXPECT_NE(text.find("\n" + e_line), std::string::npos);

  std::istringstream in(text);
  const ObservationFile f = read_rinex_obs(in, "mixed.obs");
  ASSERT_EQ(f.epochs.size(), 3u);
  EXPECT_EQ(f.report.gps_satellite_records, 3 * static_cast<int>(scene().gps.size()));
  EXPECT_EQ(f.report.galileo_satellite_records, 3 * static_cast<int>(scene().galileo.size()));
  EXPECT_TRUE(f.report.skipped_satellite_records.empty());
  for (std::size_t k = 0; k < epochs.size(); ++k) {
    const ObservationEpoch& e = f.epochs[k];
    EXPECT_EQ(e.t.seconds_since(*epochs[k].t_rx), 0.0);
    ASSERT_EQ(e.gps.size() + e.galileo.size(), epochs[k].observations.size());
    for (const ChannelObservation& c : epochs[k].observations) {
      const auto& list = c.system == GnssSystem::gps ? e.gps : e.galileo;
      const auto it = std::find_if(list.begin(), list.end(), [&](const auto& o) { return o.prn == c.prn; });
      ASSERT_NE(it, list.end()) << c.satellite().to_string();
      EXPECT_NEAR(*it->pseudorange_m, c.pseudorange_m, 0.0005);
      EXPECT_NEAR(*it->carrier_phase_cycles, -c.carrier_phase_cycles, 0.0005);
      EXPECT_NEAR(*it->doppler_hz, c.doppler_hz, 0.0005);
      EXPECT_NEAR(*it->cn0_dbhz, c.cn0_dbhz, 0.0005);
    }
  }
  // The ranges read back fix where they were made, the offset with them.
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solve_read_epoch(solver, f.epochs[0]);
  ASSERT_TRUE(p.valid) << p.reason;
  EXPECT_LT((p.r_ecef_m - scene().r_ecef_m).norm(), 0.01);
  EXPECT_NEAR(p.system_offset_m.value_or(0.0), scene().galileo_offset_m, 0.01);
}

TEST(GnssRinexObs, AGalileoOnlyFileIsTypeEAndReadsBack) {
  RinexObsHeader h;
  h.systems = {GnssSystem::galileo};
  const std::string text = rinex3_observation_file(h, receiver_epochs({GnssSystem::galileo}, 2, 0.0));
  EXPECT_EQ(lines_of(text)[0].substr(40, 20), "E (GALILEO)         ");
  EXPECT_EQ(text.find("G    4"), std::string::npos);
  std::istringstream in(text);
  const ObservationFile f = read_rinex_obs(in, "galileo.obs");
  ASSERT_EQ(f.epochs.size(), 2u);
  EXPECT_TRUE(f.epochs[0].gps.empty());
  EXPECT_EQ(f.epochs[0].galileo.size(), scene().galileo.size());
  EXPECT_EQ(f.report.time_system, "GPS");
}

TEST(GnssRinexObs, AGpsOnlyHeaderLeavesGalileoSatellitesOut) {
  const std::vector<ReceiverEpoch> epochs = receiver_epochs({GnssSystem::gps, GnssSystem::galileo}, 1, 0.0);
  const std::string text = rinex3_observation_file(RinexObsHeader{}, epochs);
  EXPECT_EQ(text.find("\nE"), std::string::npos);
  EXPECT_NE(text.find(fmt::format("  0{:3d}\n", scene().gps.size())), std::string::npos);
}

/// Each line a sentence whose checksum is right; returns the sentences' bodies.
std::vector<std::string> checked_sentences(const std::string& text) {
  std::vector<std::string> bodies;
  for (std::string line : lines_of(text)) {
    EXPECT_EQ(line.back(), '\r');
    line.pop_back();
    EXPECT_EQ(line[0], '$');
    const std::size_t star = line.find('*');
    EXPECT_EQ(star, line.size() - 3) << line;
    const std::string body = line.substr(1, star - 1);
    EXPECT_EQ(line.substr(star), nmea_checksum(body)) << line;
    bodies.push_back(body);
  }
  return bodies;
}

std::map<SatelliteId, double> cn0_of(const std::vector<PseudorangeObservation>& obs) {
  std::map<SatelliteId, double> cn0;
  for (const auto& o : obs) cn0[o.satellite()] = o.cn0_dbhz;
  return cn0;
}

TEST(GnssNmea, BothSystemsGiveGnTalkersAndAGsaPerSystem) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(2);
  const std::vector<PseudorangeObservation> obs = s.both_obs(s.t_rx, 0.0, rng);
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solver.solve(s.t_rx, obs, s.gps, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  const std::vector<std::string> b = checked_sentences(nmea_sentences(p, cn0_of(obs), 18));
  ASSERT_GE(b.size(), 6u);
  EXPECT_EQ(b[0].substr(0, 6), "GNGGA,");
  EXPECT_NE(b[0].find(fmt::format(",1,{:02d},", p.used_satellites.size())), std::string::npos) << b[0];
  EXPECT_EQ(b[1].substr(0, 6), "GNRMC,");
  EXPECT_EQ(b[2].substr(0, 6), "GNGSA,");
  EXPECT_EQ(b[2].substr(b[2].size() - 2), ",1");  // NMEA 4.1 system ID: GPS
  EXPECT_EQ(b[3].substr(0, 6), "GNGSA,");
  EXPECT_EQ(b[3].substr(b[3].size() - 2), ",3");  // Galileo
  EXPECT_NE(b[3].find(fmt::format(",{:02d},", s.galileo.begin()->first)), std::string::npos) << b[3];
  int gp_gsv = 0, ga_gsv = 0, ga_listed = 0;
  for (const std::string& body : b) {
    gp_gsv += body.rfind("GPGSV,", 0) == 0;
    if (body.rfind("GAGSV,", 0) == 0) {
      ++ga_gsv;
      EXPECT_EQ(std::stoi(body.substr(10, 2)), static_cast<int>(s.galileo.size())) << body;
      ga_listed += static_cast<int>(std::count(body.begin(), body.end(), ',') - 3) / 4;
    }
  }
  EXPECT_EQ(gp_gsv, static_cast<int>((s.gps.size() + 3) / 4));
  EXPECT_EQ(ga_gsv, static_cast<int>((s.galileo.size() + 3) / 4));
  EXPECT_EQ(ga_listed, static_cast<int>(s.galileo.size()));
}

TEST(GnssNmea, GalileoAloneGivesGaTalkers) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(2);
  const std::vector<PseudorangeObservation> obs = s.galileo_obs(s.t_rx, 0.0, rng);
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solver.solve(s.t_rx, obs, {}, s.galileo, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  const std::vector<std::string> b = checked_sentences(nmea_sentences(p, cn0_of(obs), 18));
  EXPECT_EQ(b[0].substr(0, 6), "GAGGA,");
  EXPECT_EQ(b[1].substr(0, 6), "GARMC,");
  EXPECT_EQ(b[2].substr(0, 6), "GAGSA,");
  EXPECT_EQ(b[2].substr(b[2].size() - 2), ",3");
  for (std::size_t k = 3; k < b.size(); ++k) EXPECT_EQ(b[k].substr(0, 6), "GAGSV,");
}

TEST(GnssNmea, GpsAloneKeepsTheGpTalkerWithoutSystemIds) {
  const GnssScene& s = scene();
  std::mt19937_64 rng(2);
  const std::vector<PseudorangeObservation> obs = s.gps_obs(s.t_rx, 0.0, rng);
  PvtSolver solver = vacuum_solver();
  const PvtSolution p = solver.solve(s.t_rx, obs, s.gps, s.gps_nav.iono);
  ASSERT_TRUE(p.valid) << p.reason;
  const std::vector<std::string> b = checked_sentences(nmea_sentences(p, cn0_of(obs), 18));
  for (const std::string& body : b) EXPECT_EQ(body.substr(0, 2), "GP") << body;
  EXPECT_EQ(b[2].substr(0, 5), "GPGSA");
  EXPECT_EQ(std::count(b[2].begin(), b[2].end(), ','), 17);  // 2 + 12 satellites + 3 DOPs: no system ID
}

// ---- RTKLIB cross-check -------------------------------------------------------------------

/// Both systems' records through the project's RINEX 3 writer: a mixed file, so RTKLIB also
/// reads back what the writer makes of Galileo records.
std::string mixed_nav_file() {
  const GnssScene& s = scene();
  NavData nav = s.gps_nav;
  nav.ephemerides.clear();
  for (const auto& [prn, e] : s.gps) nav.ephemerides.push_back(e);
  for (const auto& [prn, e] : s.galileo) nav.galileo_ephemerides.push_back(e);
  std::ostringstream out;
  write_rinex3_nav(out, nav, "deepnav test");
  EXPECT_NE(out.str().find("M: MIXED"), std::string::npos);
  return out.str();
}

TEST(GnssRtklibCrossCheck, MixedFixAgreesWithRnx2rtkp) {
  if (std::system("command -v rnx2rtkp > /dev/null 2>&1") != 0)
    GTEST_FAIL() << "rnx2rtkp (RTKLIB) is not installed: install the Debian package rtklib "
                    "(scripts/install_deps.sh installs it)";
  const fs::path dir = fs::path(DEEPNAV_BINARY_DIR) / "test_output" / "rtklib_gnss_crosscheck";
  fs::create_directories(dir);
  const std::vector<GnssSystem> both = {GnssSystem::gps, GnssSystem::galileo};
  // Exact ranges (to the file's millimetre): the two fixes then differ only where their models
  // do (satellite orbits, clocks, group delays, the inter-system clock), not by their weights.
  const std::vector<ReceiverEpoch> epochs = receiver_epochs(both, 3, 0.0);
  RinexObsHeader h;
  h.systems = both;
  h.approx_position_ecef_m = scene().r_ecef_m + Eigen::Vector3d(1000.0, -1000.0, 500.0);
  std::ofstream(dir / "mixed.obs") << rinex3_observation_file(h, epochs);
  std::ofstream(dir / "mixed.nav") << mixed_nav_file();
  std::ofstream(dir / "opts.conf") << "pos1-posmode=single\npos1-frequency=l1\npos1-elmask=5\npos1-ionoopt=off\n"
                                      "pos1-tropopt=off\npos1-tidecorr=off\npos1-sateph=brdc\npos1-navsys=9\n"
                                      "out-solformat=xyz\nout-outhead=on\nout-timesys=gpst\nout-timeform=tow\n"
                                      "out-timendec=3\nout-outstat=residual\n";
  const std::string cmd = fmt::format(
      "cd '{}' && rnx2rtkp -k opts.conf -sys G,E -o mixed.pos mixed.obs mixed.nav > mixed.pos.log 2>&1", dir.string());
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::map<double, Eigen::Vector3d> rtklib;
  std::map<double, int> rtklib_satellites;
  std::ifstream pos(dir / "mixed.pos");
  for (std::string line; std::getline(pos, line);) {
    if (line.empty() || line[0] == '%') continue;
    std::istringstream in(line);
    int week = 0, q = 0, ns = 0;
    double tow = 0, x = 0, y = 0, z = 0;
    if (in >> week >> tow >> x >> y >> z >> q >> ns) {
      rtklib[tow] = {x, y, z};
      rtklib_satellites[tow] = ns;
    }
  }
  // $CLK,week,tow,status,receiver,GPS clock,GLONASS,Galileo,BeiDou offsets (ns).
  std::map<double, std::pair<double, double>> rtklib_clocks_ns;
  std::ifstream stat(dir / "mixed.pos.stat");
  for (std::string line; std::getline(stat, line);) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string item; std::getline(ss, item, ',');) f.push_back(item);
    if (f.size() >= 9 && f[0] == "$CLK") rtklib_clocks_ns[std::stod(f[2])] = {std::stod(f[5]), std::stod(f[7])};
  }
  // Our fix of the same file read back.
  std::ifstream obs_in(dir / "mixed.obs");
  const ObservationFile f = read_rinex_obs(obs_in, "mixed.obs");
  PvtSolver solver = vacuum_solver();
  ASSERT_EQ(f.epochs.size(), epochs.size());
  for (const ObservationEpoch& e : f.epochs) {
    const PvtSolution p = solve_read_epoch(solver, e);
    ASSERT_TRUE(p.valid) << p.reason;
    EXPECT_GT(p.used_count(GnssSystem::galileo), 3);
    // RTKLIB tags its solution with the receiver time less its clock estimate.
    const auto it =
        std::find_if(rtklib.begin(), rtklib.end(), [&](const auto& kv) { return std::abs(kv.first - e.t.sow) < 0.01; });
    ASSERT_NE(it, rtklib.end()) << "no RTKLIB solution at " << e.t.sow << "; see " << (dir / "mixed.pos.log");
    // RTKLIB used the Galileo satellites too (exact ranges would fix GPS alone as well).
    EXPECT_EQ(rtklib_satellites.at(it->first), static_cast<int>(p.used_satellites.size()));
    // Measured: a millimetre apart; a model difference of a decimetre would show.
    const double apart = (it->second - p.r_ecef_m).norm();
    EXPECT_LT(apart, 0.05) << "RTKLIB " << it->second.transpose() << " ours " << p.r_ecef_m.transpose();
    // Its receiver clock and Galileo offset are ours too.
    ASSERT_EQ(rtklib_clocks_ns.count(it->first), 1u) << "no $CLK record at " << it->first;
    const auto [gps_ns, galileo_ns] = rtklib_clocks_ns.at(it->first);
    EXPECT_NEAR(gps_ns * 1e-9 * gps::kSpeedOfLight_mps, p.clock_bias_m, 0.05);
    EXPECT_NEAR(galileo_ns * 1e-9 * gps::kSpeedOfLight_mps, p.system_offset_m.value_or(0.0), 0.05);
    std::printf("tow %.0f: RTKLIB and deepnav GPS+Galileo fixes %.3f m apart (deepnav %.2f m from truth)\n", e.t.sow,
                apart, (p.r_ecef_m - scene().r_ecef_m).norm());
  }
}

}  // namespace
}  // namespace deepnav
