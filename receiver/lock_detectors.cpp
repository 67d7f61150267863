#include "receiver/lock_detectors.hpp"

#include <cmath>
#include <numeric>

namespace deepnav {

void LockDetector::add(const std::complex<double>& prompt, const std::complex<double>& noise, double t) {
  // A new integration length (1 ms -> 10 ms after bit sync) starts a new window; the one-
  // sample jitter of code-period lengths does not.
  if (std::abs(t - integration_s_) > 0.25e-3) reset();
  integration_s_ = t;
  const double p2 = std::norm(prompt);
  prompt_power_.push_back(p2);
  noise_power_.push_back(std::norm(noise));
  abs_i_.push_back(std::abs(prompt.real()));
  abs_q_.push_back(std::abs(prompt.imag()));
  while (prompt_power_.size() > window_) {
    prompt_power_.pop_front();
    noise_power_.pop_front();
    abs_i_.pop_front();
    abs_q_.pop_front();
  }
}

double LockDetector::cn0_dbhz() const {
  if (prompt_power_.empty()) return 0.0;
  const double p = std::accumulate(prompt_power_.begin(), prompt_power_.end(), 0.0) / prompt_power_.size();
  const double n = std::accumulate(noise_power_.begin(), noise_power_.end(), 0.0) / noise_power_.size();
  if (n <= 0.0 || p <= n) return 0.0;
  return 10.0 * std::log10((p - n) / (n * integration_s_));
}

double LockDetector::phase_lock_indicator() const {
  const double i = std::accumulate(abs_i_.begin(), abs_i_.end(), 0.0);
  const double q = std::accumulate(abs_q_.begin(), abs_q_.end(), 0.0);
  return q > 0.0 ? i / q : 0.0;
}

void LockDetector::reset() {
  prompt_power_.clear();
  noise_power_.clear();
  abs_i_.clear();
  abs_q_.clear();
}

}  // namespace deepnav
