#include "aiding/navigation_session.hpp"

#include <exception>
#include <stdexcept>

#include "receiver/mitigation/mitigation_sample_source.hpp"

namespace deepnav::aiding {
namespace {

/// The aided solution in the receiver's PVT form (DOPs and satellites from the receiver's own).
PvtSolution aided_solution(const AidedEpoch& a) {
  PvtSolution p = a.receiver.pvt;
  p.valid = true;
  if (a.receiver.t_rx) p.t = *a.receiver.t_rx;
  p.r_ecef_m = a.r_ecef_m;
  p.v_ecef_mps = a.v_ecef_mps;
  p.llh = a.llh;
  p.clock_bias_m = a.clock_bias_m;
  p.clock_drift_mps = a.clock_drift_mps;
  return p;
}

int gnss_measurements(const AidedEpoch& a) {
  switch (a.coupling) {
    case NavMode::ultra:
      return a.measuring_channels;
    case NavMode::tight:
      return static_cast<int>(a.receiver.observations.size());
    case NavMode::coast:
      return 0;
    default:
      return a.receiver.pvt.valid ? static_cast<int>(a.receiver.pvt.used_satellites.size()) : 0;
  }
}

}  // namespace

nlohmann::json mode_changes_json(const std::vector<ModeChange>& changes) {
  nlohmann::json out = nlohmann::json::array();
  for (const ModeChange& c : changes)
    out.push_back({{"t_s", c.t_s}, {"from", to_string(c.from)}, {"to", to_string(c.to)}, {"reason", c.reason}});
  return out;
}

NavigationSession::NavigationSession(NavigationSessionConfig config, SampleSource& source, std::optional<ImuLog> imu,
                                     std::optional<double> duration_s)
    : config_(std::move(config)), mitigated_(std::make_unique<MitigationSampleSource>(source, config_.mitigation)) {
  if (config_.navigator.mode == NavMode::scalar) {
    scalar_ = std::make_unique<GnssReceiver>(config_.navigator.receiver, *mitigated_);
  } else {
    if (!imu)
      throw std::invalid_argument(std::string("mode ") + to_string(config_.navigator.mode) + " needs an IMU log");
    aided_ = std::make_unique<AidedReceiver>(config_.navigator, *mitigated_, std::move(*imu), duration_s);
  }
  if (config_.assisted_iono) receiver().set_assisted_iono(*config_.assisted_iono);
  if (config_.assisted_ephemerides) receiver().set_assisted_ephemerides(*config_.assisted_ephemerides);
}

NavigationSession::~NavigationSession() = default;

GnssReceiver& NavigationSession::receiver() { return aided_ ? aided_->receiver() : *scalar_; }

void NavigationSession::hand_out(const ReceiverEpoch& ep, const AidedEpoch* a) {
  if (a) seconds_in_mode_[to_string(a->mode)] += 1.0 / config_.navigator.receiver.observation_rate_hz;
  const bool from_filter = a && a->valid;
  const PvtSolution filtered = from_filter ? aided_solution(*a) : PvtSolution{};
  const UtcParameters utc = receiver().utc();
  const NavigationEpoch e{
      ep,
      from_filter ? filtered : ep.pvt,
      from_filter,
      a ? to_string(a->mode) : "scalar",
      a ? a->filter_satellites : static_cast<int>(ep.pvt.used_satellites.size()),
      a ? gnss_measurements(*a) : (ep.pvt.valid ? static_cast<int>(ep.pvt.used_satellites.size()) : 0),
      utc.valid ? utc.delta_t_ls : 18};
  products_.on_epoch(e);
}

void NavigationSession::run(const std::vector<ProductSink*>& sinks, const std::function<void(double)>& progress) {
  products_ = ProductGroup(sinks);
  const auto on_correlation = [&](const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
    products_.on_correlation(e, ch);
  };
  std::exception_ptr failure;
  try {
    if (aided_) aided_->run([&](const AidedEpoch& a) { hand_out(a.receiver, &a); }, on_correlation, progress);
    else scalar_->run([&](const ReceiverEpoch& ep) { hand_out(ep, nullptr); }, on_correlation, progress);
  } catch (const std::exception& e) {
    // The products keep what they were given up to here; the summary says why it ended.
    failure = std::current_exception();
    run_error_ = e.what();
  }
  NavData decoded;  // from the signal only: assisted ephemerides are the input, not a product
  for (const auto& [prn, eph] : receiver().decoded_ephemerides()) decoded.ephemerides.push_back(eph);
  decoded.iono = receiver().iono();
  decoded.utc = receiver().utc();
  for (const auto& [svid, eph] : receiver().decoded_galileo_ephemerides()) decoded.galileo_ephemerides.push_back(eph);
  // I/NAV sends WN0G modulo 64: a file carries the full week, the one nearest the data.
  if (const auto ggto = receiver().ggto(); ggto && !decoded.galileo_ephemerides.empty())
    decoded.ggto = galileo::with_full_reference_week(*ggto, decoded.galileo_ephemerides.front().week);
  products_.finish(decoded);
  if (failure) std::rethrow_exception(failure);
  if (!products_.failures().empty()) throw std::runtime_error(products_.failure_message());
}

}  // namespace deepnav::aiding
