#pragma once
// An FFTW single-precision 1-D complex plan owned RAII-style. FFTW's planner is not
// thread-safe (only fftwf_execute is), and benchmarks run several receivers in threads of
// one process: every plan is made and destroyed under one process-wide lock.
#include <fftw3.h>

namespace deepnav {

class FftwPlan {
 public:
  /// FFTW_ESTIMATE plan of length n from `in` to `out` (may be the same buffer);
  /// sign is FFTW_FORWARD or FFTW_BACKWARD. Throws std::runtime_error if FFTW cannot plan.
  FftwPlan(int n, fftwf_complex* in, fftwf_complex* out, int sign);
  ~FftwPlan();
  FftwPlan(const FftwPlan&) = delete;
  FftwPlan& operator=(const FftwPlan&) = delete;
  FftwPlan(FftwPlan&& other) noexcept : plan_(other.plan_) { other.plan_ = nullptr; }
  FftwPlan& operator=(FftwPlan&& other) noexcept;
  /// Transforms the buffers given at planning.
  void execute() const { fftwf_execute(plan_); }

 private:
  fftwf_plan plan_ = nullptr;
};

}  // namespace deepnav
