#include "receiver/tracking/lock_detectors.hpp"

#include <algorithm>
#include <cmath>

namespace deepnav {
namespace {

/// The noise density changes slowly (front-end gain): its average spans this many lock windows.
constexpr std::size_t kNoiseWindowFactor = 10;

/// One hysteresis step: `count` epochs in a row that argue for the other state flip `flag`.
void hysteresis(bool& flag, int& count, bool above_on, bool below_off, int confirm) {
  const bool argues_flip = flag ? below_off : above_on;
  count = argues_flip ? count + 1 : 0;
  if (count >= confirm) {
    flag = !flag;
    count = 0;
  }
}

}  // namespace

LockDetector::LockDetector(LockThresholds thresholds) : th_(thresholds) {}

void LockDetector::add(const std::complex<double>& prompt, const std::complex<double>& noise, double t,
                       double noise_s) {
  // A new integration length (1 ms -> 10 ms after bit sync) starts a new window; the one-
  // sample jitter of code-period lengths does not. The flags keep their state meanwhile.
  if (std::abs(t - integration_s_) > 0.25e-3) {
    prompt_power_.clear();
    abs_i_.clear();
    abs_q_.clear();
    i2_.clear();
    q2_.clear();
  }
  integration_s_ = t;
  window_ = std::max<std::size_t>(20, static_cast<std::size_t>(std::lround(th_.window_s / t)));
  if (noise_s < 0.0) noise_s = t;
  if (noise_s > 0.0) noise_power_.push(std::norm(noise) / noise_s, kNoiseWindowFactor * window_);
  prompt_power_.push(std::norm(prompt), window_);
  abs_i_.push(std::abs(prompt.real()), window_);
  abs_q_.push(std::abs(prompt.imag()), window_);
  i2_.push(prompt.real() * prompt.real(), window_);
  q2_.push(prompt.imag() * prompt.imag(), window_);
  update_flags();
}

void LockDetector::update_flags() {
  if (!ready()) return;
  const double ind = phase_lock_indicator(), cn0 = cn0_dbhz();
  hysteresis(pll_lock_, pll_count_, ind > th_.pll_on, ind < th_.pll_off, th_.confirm_epochs);
  hysteresis(code_lock_, code_count_, cn0 > th_.code_on_dbhz, cn0 < th_.code_off_dbhz, th_.confirm_epochs);
}

double LockDetector::cn0_dbhz() const {
  if (prompt_power_.empty()) return 0.0;
  const double p = prompt_power_.mean(), n = noise_power_.mean() * integration_s_;
  if (n <= 0.0 || p <= n) return 0.0;
  return 10.0 * std::log10((p - n) / (n * integration_s_));
}

double LockDetector::phase_lock_indicator() const {
  const double i = abs_i_.sum(), q = abs_q_.sum();
  return q > 0.0 ? i / q : 0.0;
}

double LockDetector::cos_two_phi() const {
  const double i = i2_.sum(), q = q2_.sum();
  return i + q > 0.0 ? (i - q) / (i + q) : 0.0;
}

void LockDetector::reset() {
  prompt_power_.clear();
  noise_power_.clear();
  abs_i_.clear();
  abs_q_.clear();
  i2_.clear();
  q2_.clear();
  pll_lock_ = code_lock_ = false;
  pll_count_ = code_count_ = 0;
}

}  // namespace deepnav
