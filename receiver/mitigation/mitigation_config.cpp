#include "receiver/mitigation/mitigation_config.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <stdexcept>

namespace deepnav {
namespace {

struct ModeName {
  MitigationMode mode;
  const char* name;
};
constexpr ModeName kModeNames[] = {{MitigationMode::none, "none"},
                                   {MitigationMode::notch, "notch"},
                                   {MitigationMode::excision, "excision"},
                                   {MitigationMode::blanking, "blanking"},
                                   {MitigationMode::automatic, "auto"}};

void require(bool ok, const char* field, double value, const char* expected) {
  if (!ok) throw std::invalid_argument(fmt::format("mitigation {} = {}: expected {}", field, value, expected));
}

}  // namespace

MitigationMode parse_mitigation_mode(const std::string& name) {
  for (const auto& m : kModeNames)
    if (name == m.name) return m.mode;
  throw std::invalid_argument(
      fmt::format("unknown mitigation '{}': expected one of {}", name, fmt::join(mitigation_mode_names(), ", ")));
}

std::string to_string(MitigationMode mode) {
  for (const auto& m : kModeNames)
    if (mode == m.mode) return m.name;
  return "?";
}

std::vector<std::string> mitigation_mode_names() {
  std::vector<std::string> names;
  for (const auto& m : kModeNames) names.emplace_back(m.name);
  return names;
}

void validate_mitigation(const MitigationConfig& c, double sample_rate_hz) {
  require(std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0, "sample rate", sample_rate_hz, "> 0 Hz");
  const int n = c.excision_fft_size;
  require(n >= 64 && n <= 16384 && (n & (n - 1)) == 0, "excision_fft_size", n, "a power of two in [64, 16384]");
  require(std::isfinite(c.excision_threshold_db) && c.excision_threshold_db >= 3.0 && c.excision_threshold_db <= 60.0,
          "excision_threshold_db", c.excision_threshold_db, "3..60 dB");
  require(std::isfinite(c.blanking_threshold_db) && c.blanking_threshold_db >= 3.0 && c.blanking_threshold_db <= 60.0,
          "blanking_threshold_db", c.blanking_threshold_db, "3..60 dB");
  require(c.blanking_guard_samples >= 0 && c.blanking_guard_samples <= 4096, "blanking_guard_samples",
          c.blanking_guard_samples, "0..4096");
  require(std::isfinite(c.blanking_noise_time_constant_s) &&
              c.blanking_noise_time_constant_s * sample_rate_hz >= 16.0 && c.blanking_noise_time_constant_s <= 10.0,
          "blanking_noise_time_constant_s", c.blanking_noise_time_constant_s, "at least 16 samples and at most 10 s");
  require(std::isfinite(c.notch_pole_radius) && c.notch_pole_radius > 0.0 && c.notch_pole_radius < 1.0,
          "notch_pole_radius", c.notch_pole_radius, "in (0, 1)");
  require(std::isfinite(c.notch_step) && c.notch_step > 0.0 && c.notch_step <= 1.0, "notch_step", c.notch_step,
          "in (0, 1]");
}

}  // namespace deepnav
