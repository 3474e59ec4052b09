#include "grainflow/analysis/fft.hpp"

#include <fftw3.h>

#include <mutex>
#include <new>
#include <stdexcept>
#include <utility>

namespace grainflow::analysis {
namespace {

// FFTW's planner (fftw_plan_*, fftw_destroy_plan) shares global state; fftw_execute does not.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

fftw_complex* as_fftw(void* p) { return static_cast<fftw_complex*>(p); }
fftw_plan as_plan(void* p) { return static_cast<fftw_plan>(p); }

}  // namespace

std::size_t good_fft_size(std::size_t n) {
  if (n <= 1) return 1;
  for (std::size_t m = n;; ++m) {
    std::size_t r = m;
    for (std::size_t p : {2u, 3u, 5u, 7u})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

RealFft::RealFft(std::size_t n) : n_(n) {
  if (n == 0) throw std::invalid_argument("RealFft: length must be at least 1");
  real_ = fftw_alloc_real(n);
  complex_ = fftw_alloc_complex(n / 2 + 1);
  if (!real_ || !complex_) {
    release();
    throw std::bad_alloc();
  }
  const int len = static_cast<int>(n);
  {
    std::lock_guard lock(planner_mutex());
    forward_plan_ = fftw_plan_dft_r2c_1d(len, real_, as_fftw(complex_), FFTW_ESTIMATE);
    inverse_plan_ = fftw_plan_dft_c2r_1d(len, as_fftw(complex_), real_, FFTW_ESTIMATE);
  }
  if (!forward_plan_ || !inverse_plan_) {
    release();
    throw std::runtime_error("RealFft: FFTW could not create a plan");
  }
}

RealFft::~RealFft() { release(); }

RealFft::RealFft(RealFft&& other) noexcept
    : n_(std::exchange(other.n_, 0)),
      real_(std::exchange(other.real_, nullptr)),
      complex_(std::exchange(other.complex_, nullptr)),
      forward_plan_(std::exchange(other.forward_plan_, nullptr)),
      inverse_plan_(std::exchange(other.inverse_plan_, nullptr)) {}

RealFft& RealFft::operator=(RealFft&& other) noexcept {
  if (this != &other) {
    release();
    n_ = std::exchange(other.n_, 0);
    real_ = std::exchange(other.real_, nullptr);
    complex_ = std::exchange(other.complex_, nullptr);
    forward_plan_ = std::exchange(other.forward_plan_, nullptr);
    inverse_plan_ = std::exchange(other.inverse_plan_, nullptr);
  }
  return *this;
}

void RealFft::release() noexcept {
  if (forward_plan_ || inverse_plan_) {
    std::lock_guard lock(planner_mutex());
    if (forward_plan_) fftw_destroy_plan(as_plan(forward_plan_));
    if (inverse_plan_) fftw_destroy_plan(as_plan(inverse_plan_));
  }
  forward_plan_ = inverse_plan_ = nullptr;
  fftw_free(real_);
  fftw_free(complex_);
  real_ = nullptr;
  complex_ = nullptr;
}

void RealFft::forward(std::span<const double> x, std::span<std::complex<double>> spectrum) {
  if (x.size() > n_ || spectrum.size() != spectrum_size())
    throw std::invalid_argument("RealFft::forward: input longer than the transform or spectrum of the wrong size");
  std::size_t j = 0;
  for (; j < x.size(); ++j) real_[j] = x[j];
  for (; j < n_; ++j) real_[j] = 0.0;
  fftw_execute(as_plan(forward_plan_));
  const fftw_complex* c = as_fftw(complex_);
  for (std::size_t k = 0; k < spectrum.size(); ++k) spectrum[k] = {c[k][0], c[k][1]};
}

void RealFft::inverse(std::span<const std::complex<double>> spectrum, std::span<double> x) {
  if (x.size() > n_ || spectrum.size() != spectrum_size())
    throw std::invalid_argument("RealFft::inverse: output longer than the transform or spectrum of the wrong size");
  // The c2r transform overwrites its input, which is why it works on the object's own copy.
  fftw_complex* c = as_fftw(complex_);
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    c[k][0] = spectrum[k].real();
    c[k][1] = spectrum[k].imag();
  }
  fftw_execute(as_plan(inverse_plan_));
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = real_[j];
}

}  // namespace grainflow::analysis
