// A small RAII wrapper over FFTW's real-to-complex and complex-to-real transforms of one length,
// used by the correlation, mean-square-displacement and spectrum estimators of this directory.
#pragma once

#include <complex>
#include <cstddef>
#include <span>

namespace grainflow::analysis {

// The smallest length >= n of the form 2^a 3^b 5^c 7^d, for which FFTW is fastest.
std::size_t good_fft_size(std::size_t n);

// Forward and inverse real FFT of one length n, each object with its own aligned buffers and plans
// (FFTW_ESTIMATE: planning costs microseconds, no measurement). Conventions are FFTW's:
//   forward  X_k = sum_{j<n} x_j exp(-2 pi i j k / n),  k = 0 .. n/2 (the non-negative half),
//   inverse  x_j = sum over the full Hermitian spectrum, unnormalised: inverse(forward(x)) = n x.
// Plan creation and destruction go through one mutex because FFTW's planner is not thread-safe;
// executing plans is, so distinct objects may be used concurrently (one object: one thread at a time).
class RealFft {
 public:
  explicit RealFft(std::size_t n);  // n >= 1
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;
  RealFft(RealFft&& other) noexcept;
  RealFft& operator=(RealFft&& other) noexcept;

  std::size_t size() const { return n_; }
  std::size_t spectrum_size() const { return n_ / 2 + 1; }

  // x.size() <= n: the missing tail counts as zeros (zero padding); spectrum.size() == n/2 + 1.
  void forward(std::span<const double> x, std::span<std::complex<double>> spectrum);
  // spectrum.size() == n/2 + 1; x.size() <= n receives the first x.size() values of the result.
  void inverse(std::span<const std::complex<double>> spectrum, std::span<double> x);

 private:
  void release() noexcept;

  std::size_t n_ = 0;
  double* real_ = nullptr;   // fftw_malloc'd, n values
  void* complex_ = nullptr;  // fftw_complex[n/2 + 1], kept opaque so fftw3.h stays out of headers
  void* forward_plan_ = nullptr;
  void* inverse_plan_ = nullptr;
};

}  // namespace grainflow::analysis
