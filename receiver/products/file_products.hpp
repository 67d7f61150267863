#pragma once
// The receiver's file products, each a ProductSink writing as the run goes:
//   pvt.csv       one row per fix (the run's solution, aided where it is)
//   tracking.csv  one row per correlator integration of every channel
//   fixes.nmea    GGA, RMC, GSA, GSV per fix
//   track.kml, track.gpx
//   obs.rnx       RINEX 3.04 observations (epochs before the first fix are held until it
//                 gives the header's approximate position)
//   nav.rnx       RINEX 3.04 navigation data the run decoded (written at the end)
#include <memory>
#include <string>
#include <vector>

#include "receiver/products/product_sink.hpp"
#include "receiver/products/rinex_obs_writer.hpp"
#include "signals/text_output_file.hpp"

namespace deepnav {

/// A product that is one file, complete once the run has ended.
class FileSink : public ProductSink {
 public:
  void finish(const NavData&) override { file_.commit(); }
  void abandon() noexcept override { file_.fail(); }
  std::string name() const override;

 protected:
  explicit FileSink(const std::string& path) : file_(path) {}
  TextOutputFile file_;
};

class PvtCsvSink : public FileSink {
 public:
  explicit PvtCsvSink(const std::string& path);
  void on_epoch(const NavigationEpoch& e) override;
};

class TrackingCsvSink : public FileSink {
 public:
  explicit TrackingCsvSink(const std::string& path);
  void on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) override;
};

class NmeaSink : public FileSink {
 public:
  explicit NmeaSink(const std::string& path) : FileSink(path) {}
  void on_epoch(const NavigationEpoch& e) override;
};

/// KML and GPX tracks; `name`: the track's name (the input's file name).
class TrackSink : public ProductSink {
 public:
  TrackSink(const std::string& kml_path, const std::string& gpx_path, const std::string& name);
  void on_epoch(const NavigationEpoch& e) override;
  void finish(const NavData&) override;
  void abandon() noexcept override;
  std::string name() const override { return "track.kml/track.gpx"; }

 private:
  TextOutputFile kml_, gpx_;
};

class RinexObsSink : public ProductSink {
 public:
  /// `systems`: those the receiver tracks (the file declares them all from its header on).
  RinexObsSink(const std::string& path, double interval_s, std::vector<GnssSystem> systems = {GnssSystem::gps});
  void on_epoch(const NavigationEpoch& e) override;
  void finish(const NavData&) override;
  void abandon() noexcept override { file_.fail(); }
  std::string name() const override;

 private:
  void write_header(const Eigen::Vector3d& approx_position_ecef_m);
  TextOutputFile file_;
  RinexObsHeader header_;
  bool header_written_ = false;
  std::optional<GpsTime> first_observation_;
  std::vector<ReceiverEpoch> held_;  ///< epochs before the first fix
};

class RinexNavSink : public FileSink {
 public:
  explicit RinexNavSink(const std::string& path) : FileSink(path) {}
  void finish(const NavData& decoded) override;
};

/// The files of file_products(), in its order.
std::vector<std::string> file_product_names();

/// All of the above in `out_dir`, named as listed; `systems`: those the receiver tracks
/// (what obs.rnx declares).
std::vector<std::unique_ptr<ProductSink>> file_products(const std::string& out_dir, const std::string& track_name,
                                                        double observation_interval_s,
                                                        const std::vector<GnssSystem>& systems = {GnssSystem::gps});

}  // namespace deepnav
