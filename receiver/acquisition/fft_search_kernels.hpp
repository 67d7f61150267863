#pragma once
// The pieces an FFT parallel code-phase search is made of, shared by the GPS L1 C/A search
// (acquisition.hpp) and the Galileo E1 one (galileo_acquisition.hpp): FFTW-aligned buffers,
// the spectrum product and power accumulation written so that they vectorise, and the
// choice of a fast transform size.
#include <fftw3.h>

#include <algorithm>
#include <complex>
#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace deepnav::acquisition_kernels {

/// fftwf_complex buffers owned RAII-style (FFTW's allocator keeps SIMD alignment).
struct FftwBuffer {
  explicit FftwBuffer(std::size_t n) : data(fftwf_alloc_complex(n)), size(n) {
    if (data == nullptr) throw std::bad_alloc();
  }
  ~FftwBuffer() { fftwf_free(data); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  FftwBuffer(FftwBuffer&& o) noexcept : data(o.data), size(o.size) { o.data = nullptr; }
  FftwBuffer& operator=(FftwBuffer&& o) noexcept {
    std::swap(data, o.data);
    std::swap(size, o.size);
    return *this;
  }
  std::complex<float>* c() { return reinterpret_cast<std::complex<float>*>(data); }
  fftwf_complex* data;
  std::size_t size;
};

/// out = a * b elementwise, written out on interleaved floats: std::complex's operator*
/// checks for NaN/inf results and does not vectorise.
inline void multiply_spectra(const std::complex<float>* a, const std::complex<float>* b, std::complex<float>* out,
                             int n) {
  const float* __restrict x = reinterpret_cast<const float*>(a);
  const float* __restrict y = reinterpret_cast<const float*>(b);
  float* __restrict z = reinterpret_cast<float*>(out);
  for (int k = 0; k < 2 * n; k += 2) {
    z[k] = x[k] * y[k] - x[k + 1] * y[k + 1];
    z[k + 1] = x[k] * y[k + 1] + x[k + 1] * y[k];
  }
}

/// row[k] += |v[k]|^2, on interleaved floats so that it vectorises.
inline void add_power(const std::complex<float>* v, float* row, int n) {
  const float* __restrict x = reinterpret_cast<const float*>(v);
  float* __restrict r = row;
  for (int k = 0; k < n; ++k) r[k] += x[2 * k] * x[2 * k] + x[2 * k + 1] * x[2 * k + 1];
}

/// Smallest n' >= n whose prime factors are all 2, 3, 5 or 7 (sizes FFTW transforms fast;
/// 4092 = 4 * 3 * 11 * 31 takes five times as long as 4096).
inline int smooth_fft_size(int n) {
  for (int m = n;; ++m) {
    int r = m;
    for (int f : {2, 3, 5, 7})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

/// Cross-correlation guard shared by the GPS and Galileo searches: a detection weaker than the
/// strongest one by more than `margin_db` is taken for another satellite's code leaking through
/// (the codes' cross-correlation sits about 20 dB down), and is withdrawn and marked.
template <class Result>
void reject_cross_correlations(std::vector<Result>& results, double margin_db) {
  double strongest = -1e9;
  for (const Result& r : results)
    if (r.detected) strongest = std::max(strongest, r.cn0_dbhz);
  for (Result& r : results) {
    if (r.detected && r.cn0_dbhz < strongest - margin_db) {
      r.detected = false;
      r.cross_correlation_suspect = true;
    }
  }
}

}  // namespace deepnav::acquisition_kernels
