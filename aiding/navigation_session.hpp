#pragma once
// One navigation run, built from one configuration: samples -> interference mitigation ->
// receiver -> (in an aided mode) the INS-aided navigator -> product sinks, with one
// solution per observation epoch (NavigationEpoch) for every sink, whatever navigates.
// `deepnav run`, the benchmarks and the end-to-end tests all run through it, so the
// wiring exists once.
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "aiding/aided_receiver.hpp"
#include "receiver/mitigation/mitigation_config.hpp"
#include "receiver/products/product_group.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav::aiding {

struct NavigationSessionConfig {
  /// navigator.mode scalar: the receiver alone (navigator.receiver is the receiver's
  /// configuration in every mode; the rest applies to the aided modes).
  AidedReceiverConfig navigator;
  MitigationConfig mitigation;  ///< mode none: samples pass untouched
  /// Assistance until the broadcast data are decoded: ionosphere parameters, ephemerides.
  std::optional<IonoParameters> assisted_iono;
  std::optional<NavData> assisted_ephemerides;
};

/// Mode changes as summary.json and the jamming points report them.
nlohmann::json mode_changes_json(const std::vector<ModeChange>& changes);

class NavigationSession {
 public:
  /// `imu`: needed by the aided modes (throws std::invalid_argument without it, or when it
  /// cannot cover `duration_s`). `source` must outlive the session.
  NavigationSession(NavigationSessionConfig config, SampleSource& source, std::optional<ImuLog> imu,
                    std::optional<double> duration_s);
  ~NavigationSession();

  /// Runs to the end of the source, handing every epoch and integration to each sink, then
  /// finishes every sink (so each file takes its final name) even when the source ended
  /// early. A run that fails (an exception from the receiver or the filter) still finishes
  /// them, with what they were given up to the failure (run_error() says why, for the
  /// summary), and then rethrows. A sink that throws, while the run goes or when it
  /// finishes, is abandoned and recorded (product_failures(), at once, so a later sink can
  /// report it) without stopping the run or the others (product_group.hpp); then run()
  /// throws std::runtime_error naming the products.
  void run(const std::vector<ProductSink*>& sinks, const std::function<void(double)>& progress = {});
  const std::optional<std::string>& run_error() const { return run_error_; }
  const std::vector<ProductFailure>& product_failures() const { return products_.failures(); }

  GnssReceiver& receiver();
  /// The aided navigator (nullptr in scalar mode).
  const AidedReceiver* aided() const { return aided_.get(); }
  /// Seconds spent in each navigation mode.
  const std::map<std::string, double>& seconds_in_mode() const { return seconds_in_mode_; }

 private:
  void hand_out(const ReceiverEpoch& epoch, const AidedEpoch* aided);
  NavigationSessionConfig config_;
  std::unique_ptr<SampleSource> mitigated_;
  std::unique_ptr<AidedReceiver> aided_;
  std::unique_ptr<GnssReceiver> scalar_;
  std::map<std::string, double> seconds_in_mode_;
  std::optional<std::string> run_error_;
  ProductGroup products_;
};

}  // namespace deepnav::aiding
