#include "receiver/acquisition/fftw_plan.hpp"

#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

namespace deepnav {
namespace {

std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

FftwPlan::FftwPlan(int n, fftwf_complex* in, fftwf_complex* out, int sign) {
  {
    const std::lock_guard<std::mutex> lock(planner_mutex());
    plan_ = fftwf_plan_dft_1d(n, in, out, sign, FFTW_ESTIMATE);
  }
  if (plan_ == nullptr) throw std::runtime_error("FFTW could not plan a transform of " + std::to_string(n) + " points");
}

FftwPlan::~FftwPlan() {
  if (plan_ == nullptr) return;
  const std::lock_guard<std::mutex> lock(planner_mutex());
  fftwf_destroy_plan(plan_);
}

FftwPlan& FftwPlan::operator=(FftwPlan&& other) noexcept {
  std::swap(plan_, other.plan_);
  return *this;
}

}  // namespace deepnav
