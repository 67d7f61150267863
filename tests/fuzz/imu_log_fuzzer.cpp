// IMU logs as recorders write them (ins/imu_log_reader.hpp): the input is read as a generic
// CSV with the walk's column map and units, and as a KF-GINS increments file. What a read
// that succeeds promises is checked: samples in strictly increasing time, finite, and
// gaps that lie between two of them.
#include <cmath>
#include <sstream>

#include "ins/imu_log_reader.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

constexpr const char* kName = "fuzz_imu.log";

void check_promises(const deepnav::ImuLogRead& r) {
  const auto& samples = r.log.samples;
  if (samples.empty() || r.report.samples != static_cast<int>(samples.size()))
    deepnav::fuzz::broken_promise("a read log without samples, or a report that miscounts them");
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!std::isfinite(samples[i].t_s) || !samples[i].dtheta_b_rad.allFinite() || !samples[i].dv_b_mps.allFinite())
      deepnav::fuzz::broken_promise("a sample that is not finite");
    if (i > 0 && !(samples[i].t_s > samples[i - 1].t_s)) deepnav::fuzz::broken_promise("sample times do not increase");
  }
  for (const deepnav::ImuGap& g : r.log.gaps)
    if (!(g.t_before_s < g.t_after_s) || g.t_before_s < samples.front().t_s || g.t_after_s > samples.back().t_s)
      deepnav::fuzz::broken_promise("a gap that is not between two samples");
}

void read_as(const std::string& text, const deepnav::ImuLogOptions& options) {
  std::istringstream in(text);
  deepnav::ImuLogRead r;
  if (deepnav::fuzz::guarded([&] { r = deepnav::read_imu_log(in, kName, options); }, deepnav::fuzz::names_input(kName)))
    check_promises(r);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = deepnav::fuzz::as_text(data, size);
  deepnav::ImuLogOptions walk;
  walk.format = deepnav::ImuLogFormat::csv;
  walk.columns = "ax,ay,az,gx,gy,gz,t";
  walk.accel_unit = "g";
  walk.gyro_unit = "deg/s";
  walk.time_scale = 1e-3;
  walk.nominal_rate_hz = 100.0;
  read_as(text, walk);
  deepnav::ImuLogOptions kf;
  kf.format = deepnav::ImuLogFormat::kf_gins;
  read_as(text, kf);
  return 0;
}
