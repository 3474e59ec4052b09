#include "grainflow/analysis/local_quadratic_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace grainflow::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Matrix3 = std::array<std::array<double, 3>, 3>;

// Inverse of a symmetric positive-definite 3x3 matrix by cofactors.
Matrix3 inverse(const Matrix3& m) {
  Matrix3 c;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      c[k][r] = m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1];  // transposed cofactor
    }
  const double det = m[0][0] * c[0][0] + m[0][1] * c[1][0] + m[0][2] * c[2][0];
  for (auto& row : c)
    for (double& v : row) v /= det;
  return c;
}

}  // namespace

std::vector<FitPoint> local_quadratic_fit(std::span<const double> x, std::span<const double> y,
                                          std::span<const double> y_error, std::size_t window) {
  if (x.size() != y.size() || (!y_error.empty() && y_error.size() != y.size()))
    throw std::invalid_argument("local_quadratic_fit: x, y and y_error differ in length");
  if (window < 3) throw std::invalid_argument("local_quadratic_fit: the window needs at least 3 points");
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < y.size(); ++i)
    if (std::isfinite(y[i])) usable.push_back(i);
  std::vector<FitPoint> out(y.size(), FitPoint{kNaN, kNaN, kNaN});
  if (usable.size() < 3) return out;
  const std::size_t w = std::min(window, usable.size());
  for (std::size_t p = 0; p < usable.size(); ++p) {
    const std::size_t first = std::min(p > w / 2 ? p - w / 2 : 0, usable.size() - w);
    const double x0 = x[usable[p]];
    const double scale = x[usable[first + w - 1]] - x[usable[first]];  // conditions the normal equations
    // Normal equations of y = a + b t + c t^2, t = (x - x0) / scale.
    Matrix3 normal{};
    for (std::size_t j = first; j < first + w; ++j) {
      const double t = (x[usable[j]] - x0) / scale;
      const std::array<double, 3> powers{1.0, t, t * t};
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) normal[r][k] += powers[r] * powers[k];
    }
    const Matrix3 inv = inverse(normal);
    // a and b as linear combinations of the y_j: a = sum d_j y_j, b = sum c_j y_j.
    double a = 0.0, b = 0.0, variance = 0.0;
    for (std::size_t j = first; j < first + w; ++j) {
      const double t = (x[usable[j]] - x0) / scale;
      const double d = inv[0][0] + inv[0][1] * t + inv[0][2] * t * t;
      const double c = inv[1][0] + inv[1][1] * t + inv[1][2] * t * t;
      a += d * y[usable[j]];
      b += c * y[usable[j]];
      const double e = y_error.empty() ? kNaN : y_error[usable[j]];
      variance += c * c * e * e;
    }
    out[usable[p]] = FitPoint{a, b / scale, std::sqrt(variance) / scale};
  }
  return out;
}

}  // namespace grainflow::analysis
