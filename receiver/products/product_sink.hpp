#pragma once
// What a run hands its products at each observation epoch, whatever navigates (the
// receiver alone or an aided filter), and the interface of a product that takes it. Each
// product writes as the run goes, to a file that takes its final name only in finish()
// (text_output_file.hpp): memory stays flat with run length. A run that fails still
// finishes its products (what was written up to the failure, and the run's summary says
// so); a product whose writer fails is reported without costing the others
// (product_group.hpp).
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "receiver/gnss_receiver.hpp"
#include "signals/rinex_nav.hpp"

namespace deepnav {

struct NavigationEpoch {
  const ReceiverEpoch& receiver;  ///< observables and the receiver's own PVT
  /// The solution the run reports: the aided filter's where it has one, else the PVT's.
  const PvtSolution& solution;
  bool from_filter = false;  ///< `solution` is the aided filter's
  std::string_view mode;     ///< navigation mode at this epoch ("scalar", "loose", ...)
  /// Satellites the solution's last update took (the PVT's in scalar mode).
  int filter_satellites = 0;
  /// Satellites whose measurements the solution used: the PVT's in scalar and loose mode,
  /// observables in tight mode, discriminator measurements in ultra-tight mode.
  int gnss_measurements = 0;
  int leap_seconds = 18;  ///< GPS - UTC (broadcast once decoded)
};

class ProductSink {
 public:
  virtual ~ProductSink() = default;
  virtual void on_epoch(const NavigationEpoch&) {}
  /// Every completed integration of every channel.
  virtual void on_correlation(const CorrelatorEpoch&, const ChannelSnapshot&) {}
  /// The run has ended: write what is left and give the file its final name.
  /// `decoded`: the navigation data the run ended with (ephemerides, ionosphere, UTC).
  virtual void finish(const NavData& decoded) { (void)decoded; }
  /// The product failed (a call threw): remove what it wrote, and an earlier run's file
  /// under its name that it can no longer replace (so that none passes for this run's).
  virtual void abandon() noexcept {}
  /// What the product is called in reports ("pvt.csv"; a sink that writes no file: what it does).
  virtual std::string name() const { return "product"; }
};

/// A sink made of callables, for a caller that only watches the run (a benchmark counting
/// channels, a sweep following each channel's integrations) and writes no file.
class CallbackSink : public ProductSink {
 public:
  using EpochCallback = std::function<void(const NavigationEpoch&)>;
  using CorrelationCallback = std::function<void(const CorrelatorEpoch&, const ChannelSnapshot&)>;
  explicit CallbackSink(EpochCallback on_epoch, CorrelationCallback on_correlation = {})
      : on_epoch_(std::move(on_epoch)), on_correlation_(std::move(on_correlation)) {}
  void on_epoch(const NavigationEpoch& e) override {
    if (on_epoch_) on_epoch_(e);
  }
  void on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) override {
    if (on_correlation_) on_correlation_(e, ch);
  }

 private:
  EpochCallback on_epoch_;
  CorrelationCallback on_correlation_;
};

}  // namespace deepnav
