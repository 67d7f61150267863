// Cross-check of satellite positions and clocks against RTKLIB, an independent
// implementation of the same IS-GPS-200 algorithms.
//
// Method: for a known receiver position and epoch we synthesize a RINEX 2.11 observation
// file whose C1 pseudoranges come from OUR ephemeris code: light-time iteration with the
// Sagnac rotation (signals/sim/line_of_sight), our satellite clock including the relativistic
// term, minus TGD as an L1 C/A user applies it, receiver clock zero, no ionosphere and no
// troposphere. RTKLIB's rnx2rtkp then solves single-point positions with its ionosphere and
// troposphere models off and writes its per-satellite pseudorange residuals (stat file).
// Its navigation file holds the very records we used, copied verbatim from
// data/brdc0010.22n, so RTKLIB reads them with its own parser. If RTKLIB's satellite
// positions and clocks agree with ours, its residuals are at the level of the millimetre
// rounding of the observation file and its position equals the true one. A satellite
// position error along the line of sight or a clock error shows up in the residuals and
// the position; a common error would go into RTKLIB's receiver clock, checked as well.
// A second run gives RTKLIB the same records through our RINEX 3.04 writer.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "ins/gps_time.hpp"
#include "ins/wgs84.hpp"
#include "signals/ephemeris.hpp"
#include "signals/gps_constants.hpp"
#include "signals/rinex_nav.hpp"
#include "signals/sim/line_of_sight.hpp"

namespace deepnav {
namespace {

namespace fs = std::filesystem;

const std::string kBrdcPath = std::string(DEEPNAV_SOURCE_DIR) + "/data/brdc0010.22n";
constexpr int kBrdcHeaderLines = 8;
constexpr int kRecordLines = 8;

struct Observation {
  int prn;
  double pseudorange_m;
};

struct Epoch {
  GpsTime t;
  std::vector<Observation> obs;
};

double elevation_rad(const Eigen::Vector3d& r_rx, const wgs84::Llh& llh, const Eigen::Vector3d& r_sat) {
  const Eigen::Vector3d up(std::cos(llh.lat_rad) * std::cos(llh.lon_rad), std::cos(llh.lat_rad) * std::sin(llh.lon_rad),
                           std::sin(llh.lat_rad));
  return std::asin(up.dot((r_sat - r_rx).normalized()));
}

std::vector<std::string> file_lines(const std::string& path) {
  std::ifstream f(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(f, line);) lines.push_back(line);
  return lines;
}

void write_obs_file(const std::string& path, const std::vector<Epoch>& epochs, const Eigen::Vector3d& approx) {
  std::ofstream out(path);
  const auto header = [&](const std::string& content, const char* label) {
    out << fmt::format("{:<60}{:<20}\n", content, label);
  };
  const CalendarTime c0 = calendar_from_gps_time(epochs.front().t);
  header("     2.11           OBSERVATION DATA    G (GPS)", "RINEX VERSION / TYPE");
  header("deepnav test        deepnav             20220101 000000 UTC", "PGM / RUN BY / DATE");
  header("SYNTH", "MARKER NAME");
  header("deepnav             deepnav", "OBSERVER / AGENCY");
  header("0                   deepnav             0", "REC # / TYPE / VERS");
  header("0                   deepnav", "ANT # / TYPE");
  header(fmt::format("{:14.4f}{:14.4f}{:14.4f}", approx.x(), approx.y(), approx.z()), "APPROX POSITION XYZ");
  header("        0.0000        0.0000        0.0000", "ANTENNA: DELTA H/E/N");
  header("     1     1", "WAVELENGTH FACT L1/2");
  header("     1    C1", "# / TYPES OF OBSERV");
  header(fmt::format("{:6d}{:6d}{:6d}{:6d}{:6d}{:13.7f}     GPS", c0.year, c0.month, c0.day, c0.hour, c0.minute,
                     c0.second),
         "TIME OF FIRST OBS");
  header("", "END OF HEADER");
  for (const Epoch& ep : epochs) {
    const CalendarTime c = calendar_from_gps_time(ep.t);
    out << fmt::format(" {:02d} {:2d} {:2d} {:2d} {:2d}{:11.7f}  0{:3d}", c.year % 100, c.month, c.day, c.hour,
                       c.minute, c.second, ep.obs.size());
    for (std::size_t i = 0; i < ep.obs.size(); ++i) {
      if (i > 0 && i % 12 == 0) out << "\n" << std::string(32, ' ');
      out << fmt::format("G{:02d}", ep.obs[i].prn);
    }
    out << "\n";
    for (const Observation& o : ep.obs) out << fmt::format("{:14.3f}  \n", o.pseudorange_m);
  }
}

void write_rtklib_options(const std::string& path) {
  std::ofstream out(path);
  out << "pos1-posmode=single\n"
         "pos1-frequency=l1\n"
         "pos1-elmask=5\n"
         "pos1-ionoopt=off\n"
         "pos1-tropopt=off\n"
         "pos1-tidecorr=off\n"
         "pos1-sateph=brdc\n"
         "pos1-navsys=1\n"
         "out-solformat=xyz\n"
         "out-outhead=on\n"
         "out-timesys=gpst\n"
         "out-timeform=tow\n"
         "out-timendec=3\n"
         "out-outstat=residual\n";
}

struct RtklibResult {
  std::map<double, Eigen::Vector3d> position_by_tow;
  std::map<double, double> clock_ns_by_tow;
  std::map<std::pair<double, int>, double> residual_m;  // (tow, prn) -> pseudorange residual
};

RtklibResult run_rnx2rtkp(const fs::path& dir, const std::string& obs, const std::string& nav) {
  const fs::path pos = dir / (nav + ".pos");
  const std::string cmd = fmt::format("cd '{}' && rnx2rtkp -k opts.conf -o '{}' {} {} > '{}.log' 2>&1", dir.string(),
                                      pos.string(), obs, nav, pos.string());
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  RtklibResult r;
  for (const std::string& line : file_lines(pos.string())) {
    if (line.empty() || line[0] == '%') continue;
    std::istringstream in(line);
    int week = 0;
    double tow = 0, x = 0, y = 0, z = 0;
    if (in >> week >> tow >> x >> y >> z) r.position_by_tow[tow] = {x, y, z};
  }
  for (const std::string& line : file_lines(pos.string() + ".stat")) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string item; std::getline(ss, item, ',');) f.push_back(item);
    if (f.size() >= 9 && f[0] == "$SAT" && f[3].size() == 3 && f[3][0] == 'G' && f[4] == "1") {
      r.residual_m[{std::stod(f[2]), std::stoi(f[3].substr(1))}] = std::stod(f[7]);
    }
    if (f.size() >= 6 && f[0] == "$CLK") r.clock_ns_by_tow[std::stod(f[2])] = std::stod(f[5]);
  }
  return r;
}

class RtklibCrossCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::system("command -v rnx2rtkp > /dev/null 2>&1") != 0) {
      GTEST_FAIL() << "rnx2rtkp (RTKLIB) is not installed: install the Debian package rtklib "
                      "(scripts/install_deps.sh installs it)";
    }
    dir_ = fs::path(DEEPNAV_BINARY_DIR) / "test_output" / "rtklib_crosscheck";
    fs::create_directories(dir_);
    write_rtklib_options((dir_ / "opts.conf").string());
  }
  fs::path dir_;
};

TEST_F(RtklibCrossCheck, SatellitePositionsAndClocksAgreeToOneCentimetre) {
  const NavData nav = read_rinex_nav(kBrdcPath);
  const std::vector<std::string> brdc_lines = file_lines(kBrdcPath);
  ASSERT_EQ(brdc_lines.size(), kBrdcHeaderLines + kRecordLines * nav.ephemerides.size());

  // Receiver in Daejeon, Korea; epochs at 00:30 and 01:40 GPS time (different data sets).
  const wgs84::Llh llh{36.37 * std::numbers::pi / 180.0, 127.36 * std::numbers::pi / 180.0, 80.0};
  const Eigen::Vector3d r_rx = wgs84::llh_to_ecef(llh);
  const GpsTime midnight{2190, 518400.0};
  std::vector<Epoch> epochs = {{midnight.plus_seconds(1800.0), {}}, {midnight.plus_seconds(6000.0), {}}};

  std::vector<const Ephemeris*> used;
  NavData used_nav = nav;
  used_nav.ephemerides.clear();
  for (Epoch& ep : epochs) {
    for (int prn = 1; prn <= gps::kMaxPrn; ++prn) {
      const Ephemeris* eph = nav.select(prn, ep.t);
      if (eph == nullptr) continue;
      const LineOfSight los = line_of_sight(*eph, ep.t, r_rx, Eigen::Vector3d::Zero());
      if (elevation_rad(r_rx, llh, los.r_sat_ecef_m) < 10.0 * std::numbers::pi / 180.0) continue;
      const double sat_clock_s = los.satellite.clock_bias_s - eph->tgd_s;
      ep.obs.push_back({prn, los.range_m - gps::kSpeedOfLight_mps * sat_clock_s});
      if (std::find(used.begin(), used.end(), eph) == used.end()) {
        used.push_back(eph);
        used_nav.ephemerides.push_back(*eph);
      }
    }
    ASSERT_GE(ep.obs.size(), 6u);
  }

  // RTKLIB's navigation file: the header and the used records, verbatim.
  {
    std::ofstream out(dir_ / "used.22n");
    for (int i = 0; i < kBrdcHeaderLines; ++i) out << brdc_lines[static_cast<std::size_t>(i)] << "\n";
    for (const Ephemeris* eph : used) {
      const auto index = static_cast<std::size_t>(eph - nav.ephemerides.data());
      for (int k = 0; k < kRecordLines; ++k) {
        out << brdc_lines[kBrdcHeaderLines + kRecordLines * index + static_cast<std::size_t>(k)] << "\n";
      }
    }
  }
  {
    std::ofstream out(dir_ / "used.rnx");
    write_rinex3_nav(out, used_nav, "deepnav test");
  }
  write_obs_file((dir_ / "synth.22o").string(), epochs, r_rx + Eigen::Vector3d(1000.0, -1000.0, 500.0));

  for (const std::string nav_file : {"used.22n", "used.rnx"}) {
    SCOPED_TRACE(nav_file);
    const RtklibResult r = run_rnx2rtkp(dir_, "synth.22o", nav_file);
    for (const Epoch& ep : epochs) {
      SCOPED_TRACE(fmt::format("tow {}", ep.t.sow));
      ASSERT_EQ(r.position_by_tow.count(ep.t.sow), 1u) << "no RTKLIB solution; see " << nav_file << ".pos.log";
      const Eigen::Vector3d err = r.position_by_tow.at(ep.t.sow) - r_rx;
      EXPECT_LT(err.norm(), 0.01) << err.transpose();
      ASSERT_EQ(r.clock_ns_by_tow.count(ep.t.sow), 1u);
      EXPECT_LT(std::abs(r.clock_ns_by_tow.at(ep.t.sow)), 0.01 / gps::kSpeedOfLight_mps * 1e9);
      for (const Observation& o : ep.obs) {
        const auto key = std::make_pair(ep.t.sow, o.prn);
        ASSERT_EQ(r.residual_m.count(key), 1u) << "RTKLIB did not use PRN " << o.prn;
        EXPECT_LT(std::abs(r.residual_m.at(key)), 0.01) << "PRN " << o.prn;
      }
    }
  }
}

}  // namespace
}  // namespace deepnav
