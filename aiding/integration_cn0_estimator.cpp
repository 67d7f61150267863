#include "aiding/integration_cn0_estimator.hpp"

#include <cmath>

namespace deepnav::aiding {

IntegrationPower coherent_power(const std::complex<double>& prompt, const std::complex<double>& noise, double end_s,
                                double integration_s, double noise_s) {
  IntegrationPower p;
  p.end_s = end_s;
  p.prompt_power = std::norm(prompt);
  p.sum_t_s = integration_s;
  p.sum_t2_s2 = integration_s * integration_s;
  p.noise_power = std::norm(noise);
  p.noise_s = noise_s;
  return p;
}
namespace {

/// The noise density changes slowly (front-end gain): its average spans this many windows.
constexpr double kNoiseWindowFactor = 10.0;

/// Drops entries older than `span_s` before the newest, keeping at least `keep`.
void trim(std::deque<IntegrationPower>& d, double span_s, std::size_t keep) {
  while (d.size() > keep && d.back().end_s - d.front().end_s > span_s) d.pop_front();
}

}  // namespace

void IntegrationCn0Estimator::add(const IntegrationPower& p) {
  window_.push_back(p);
  trim(window_, window_s_, static_cast<std::size_t>(min_count_));
  if (p.noise_s > 0.0) {
    noise_window_.push_back(p);
    trim(noise_window_, kNoiseWindowFactor * window_s_, static_cast<std::size_t>(kNoiseWindowFactor * min_count_));
  }
}

void IntegrationCn0Estimator::reset() {
  window_.clear();
  noise_window_.clear();
}

bool IntegrationCn0Estimator::ready() const {
  return window_.size() >= static_cast<std::size_t>(min_count_) && !noise_window_.empty();
}

std::optional<IntegrationCn0Estimator::Estimate> IntegrationCn0Estimator::estimate() const {
  if (!ready()) return std::nullopt;
  double noise = 0.0, noise_s = 0.0;
  for (const IntegrationPower& p : noise_window_) {
    noise += p.noise_power;
    noise_s += p.noise_s;
  }
  Estimate e;
  e.n = noise / noise_s;
  double power = 0.0, t = 0.0;
  for (const IntegrationPower& p : window_) {
    power += p.prompt_power;
    t += p.sum_t_s;
    e.sum_t2 += p.sum_t2_s2;
  }
  if (!(e.n > 0.0) || !(e.sum_t2 > 0.0)) return std::nullopt;
  e.c = (power - e.n * t) / e.sum_t2;
  return e;
}

double IntegrationCn0Estimator::cn0_dbhz() const {
  const std::optional<Estimate> e = estimate();
  if (!e || !(e->c > 0.0)) return 0.0;
  return 10.0 * std::log10(e->c / e->n);
}

bool IntegrationCn0Estimator::signal_detected(double sigmas) const {
  const std::optional<Estimate> e = estimate();
  return e && e->c > sigmas * e->n / std::sqrt(e->sum_t2);
}

double IntegrationCn0Estimator::wiped_phase_lock_indicator() const {
  double i = 0.0, q = 0.0;
  int count = 0;
  for (const IntegrationPower& p : window_) {
    if (!p.data_wiped) continue;
    i += p.wiped_prompt.real();
    q += std::abs(p.wiped_prompt.imag());
    ++count;
  }
  if (count < min_count_ || !(q > 0.0)) return 0.0;
  return i / q;
}

}  // namespace deepnav::aiding
