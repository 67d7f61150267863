#include "receiver/products/file_products.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <sstream>

#include "ins/frames.hpp"
#include "receiver/products/nmea_writer.hpp"
#include "receiver/products/track_writers.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {
namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
}

std::string FileSink::name() const { return std::filesystem::path(file_.path()).filename().string(); }
std::string RinexObsSink::name() const { return std::filesystem::path(file_.path()).filename().string(); }

PvtCsvSink::PvtCsvSink(const std::string& path) : FileSink(path) {
  file_.write(
      "t_s,gps_week,gps_sow,valid,x_ecef_m,y_ecef_m,z_ecef_m,lat_deg,lon_deg,height_m,vn_mps,ve_mps,vd_mps,"
      "clock_bias_m,clock_drift_mps,satellites,gdop,pdop,hdop,vdop,excluded,mode,filter_satellites\n");
}

void PvtCsvSink::on_epoch(const NavigationEpoch& e) {
  const PvtSolution& p = e.solution;
  if (!p.valid) return;
  const Eigen::Vector3d v_ned = C_e_n(p.llh.lat_rad, p.llh.lon_rad) * p.v_ecef_mps;
  std::string excluded;
  // GPS satellites by number (as ever), others by their RINEX name (E11).
  for (const SatelliteId& sat : p.excluded_satellites) {
    if (!excluded.empty()) excluded += ' ';
    excluded += sat.system == GnssSystem::gps ? std::to_string(sat.prn) : sat.to_string();
  }
  file_.write(fmt::format(
      "{:.3f},{},{:.6f},1,{:.4f},{:.4f},{:.4f},{:.9f},{:.9f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{},{:.2f},{:.2f}"
      ",{:.2f},"
      "{:.2f},{},{},{}\n",
      e.receiver.t_s, p.t.week, p.t.sow, p.r_ecef_m.x(), p.r_ecef_m.y(), p.r_ecef_m.z(), p.llh.lat_rad * kRadToDeg,
      p.llh.lon_rad * kRadToDeg, p.llh.height_m, v_ned.x(), v_ned.y(), v_ned.z(), p.clock_bias_m, p.clock_drift_mps,
      p.used_satellites.size(), p.dops.gdop, p.dops.pdop, p.dops.hdop, p.dops.vdop, excluded, e.mode,
      e.filter_satellites));
}

TrackingCsvSink::TrackingCsvSink(const std::string& path) : FileSink(path) {
  file_.write(
      "first_sample,prn,state,integration_s,i_prompt,q_prompt,i_early,q_early,i_late,q_late,doppler_hz,code_rate_cps,"
      "cn0_dbhz\n");
}

void TrackingCsvSink::on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
  file_.write(fmt::format("{},{},{},{:.3f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.3f},{:.4f},{:.1f}\n",
                          e.first_sample, e.prn, static_cast<int>(ch.state), e.integration_s, e.prompt.real(),
                          e.prompt.imag(), e.early.real(), e.early.imag(), e.late.real(), e.late.imag(),
                          e.carrier_doppler_hz, e.code_rate_cps, ch.cn0_dbhz));
}

void NmeaSink::on_epoch(const NavigationEpoch& e) {
  if (!e.solution.valid) return;
  file_.write(nmea_sentences(e.solution, cn0_by_satellite(e.receiver), e.leap_seconds, e.mode == "coast"));
}

TrackSink::TrackSink(const std::string& kml_path, const std::string& gpx_path, const std::string& name)
    : kml_(kml_path), gpx_(gpx_path) {
  kml_.write(kml_header(name));
  gpx_.write(gpx_header(name));
}

void TrackSink::on_epoch(const NavigationEpoch& e) {
  if (!e.solution.valid) return;
  kml_.write(kml_point(e.solution));
  gpx_.write(gpx_point(e.solution, e.leap_seconds));
}

void TrackSink::finish(const NavData&) {
  kml_.write(kml_footer());
  gpx_.write(gpx_footer());
  kml_.commit();
  gpx_.commit();
}

void TrackSink::abandon() noexcept {
  kml_.fail();
  gpx_.fail();
}

RinexObsSink::RinexObsSink(const std::string& path, double interval_s, std::vector<GnssSystem> systems) : file_(path) {
  header_.interval_s = interval_s;
  header_.systems = std::move(systems);
}

void RinexObsSink::write_header(const Eigen::Vector3d& approx_position_ecef_m) {
  header_.approx_position_ecef_m = approx_position_ecef_m;
  file_.write(rinex3_observation_header(header_, first_observation_));
  for (const ReceiverEpoch& held : held_) file_.write(rinex3_observation_epoch(held, header_.systems));
  held_.clear();
  held_.shrink_to_fit();
  header_written_ = true;
}

void RinexObsSink::on_epoch(const NavigationEpoch& e) {
  if (!first_observation_ && e.receiver.t_rx) first_observation_ = e.receiver.t_rx;
  if (header_written_) return file_.write(rinex3_observation_epoch(e.receiver, header_.systems));
  held_.push_back(e.receiver);
  if (e.solution.valid) write_header(e.solution.r_ecef_m);
}

void RinexObsSink::finish(const NavData&) {
  if (!header_written_) write_header(Eigen::Vector3d::Zero());  // no fix: position unknown
  file_.commit();
}

void RinexNavSink::finish(const NavData& decoded) {
  std::ostringstream rinex;
  write_rinex3_nav(rinex, decoded, "deepnav");
  file_.write(rinex.str());
  FileSink::finish(decoded);
}

std::vector<std::string> file_product_names() {
  return {"pvt.csv", "tracking.csv", "nav.rnx", "obs.rnx", "fixes.nmea", "track.kml", "track.gpx"};
}

std::vector<std::unique_ptr<ProductSink>> file_products(const std::string& out_dir, const std::string& track_name,
                                                        double observation_interval_s,
                                                        const std::vector<GnssSystem>& systems) {
  const auto path = [&](const char* name) { return (std::filesystem::path(out_dir) / name).string(); };
  std::vector<std::unique_ptr<ProductSink>> sinks;
  sinks.push_back(std::make_unique<PvtCsvSink>(path("pvt.csv")));
  sinks.push_back(std::make_unique<TrackingCsvSink>(path("tracking.csv")));
  sinks.push_back(std::make_unique<RinexNavSink>(path("nav.rnx")));
  sinks.push_back(std::make_unique<RinexObsSink>(path("obs.rnx"), observation_interval_s, systems));
  sinks.push_back(std::make_unique<NmeaSink>(path("fixes.nmea")));
  sinks.push_back(std::make_unique<TrackSink>(path("track.kml"), path("track.gpx"), track_name));
  return sinks;
}

}  // namespace deepnav
