#pragma once
// The figures of a run that summary.json reports: epochs, fixes, time to first fix,
// satellites and PDOP of the fixes, and, given the synthesizer's truth, the errors of the
// run's solution against it.
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "receiver/products/product_sink.hpp"
#include "receiver/products/truth_file.hpp"

namespace deepnav {

/// rms, p95, max and count of a quantity's values (null when there are none).
struct ValueStatistics {
  std::vector<double> values;
  nlohmann::json json() const;
  double rms() const;
};

class RunStatistics : public ProductSink {
 public:
  /// `truth`: nullptr when the run is not scored (not owned).
  explicit RunStatistics(const TruthFile* truth) : truth_(truth) {}
  void on_epoch(const NavigationEpoch& e) override;
  std::string name() const override { return "run statistics"; }

  int epochs() const { return epochs_; }
  int fixes() const { return fixes_; }
  std::optional<double> first_fix_s() const { return first_fix_s_; }
  const ValueStatistics& satellites() const { return satellites_; }
  const ValueStatistics& pdop() const { return pdop_; }
  const ValueStatistics& horizontal_error_m() const { return horizontal_; }
  const ValueStatistics& vertical_error_m() const { return vertical_; }
  const ValueStatistics& velocity_error_mps() const { return velocity_; }

 private:
  const TruthFile* truth_;
  int epochs_ = 0, fixes_ = 0;
  std::optional<double> first_fix_s_;
  ValueStatistics satellites_, pdop_, horizontal_, vertical_, velocity_;
};

}  // namespace deepnav
