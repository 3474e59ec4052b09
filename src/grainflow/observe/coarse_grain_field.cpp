#include "grainflow/observe/coarse_grain_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "grainflow/config/case_config.hpp"

namespace grainflow::observe {
namespace {

// sum m v_a v_b is kept as its six distinct components.
constexpr int kSymmetric[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};

}  // namespace

double CoarseGrainKernel::shape(double r2) const {
  const double reach2 = reach() * reach();
  if (!(r2 < reach2)) return 0.0;
  if (kind == Kind::gaussian) return gaussian_factor(r2);
  const double q = std::sqrt(r2) / width;
  const double one_minus = 1.0 - q;
  return (1.0 + 3.0 * q) * one_minus * one_minus * one_minus;
}

// Shifted down by its value at the cutoff, so that it ends continuously there: a point whose
// distance to a cell centre rounds to either side of 3 widths gets the same field to round-off.
double CoarseGrainKernel::gaussian_factor(double d2) const {
  const double reach2 = reach() * reach();
  if (!(d2 < reach2)) return 0.0;
  const double s = 0.5 / (width * width);
  return std::exp(-s * d2) - std::exp(-s * reach2);
}

double CoarseGrainKernel::standard_deviation() const {
  return kind == Kind::gaussian ? width : lucy_standard_deviation(width, dimension);
}

CoarseGrainField::CoarseGrainField(const PeriodicBox& box, std::array<int, 3> cells, CoarseGrainKernel kernel)
    : box_(box), cells_(cells), kernel_(kernel) {
  for (int a = 0; a < 3; ++a) {
    if (cells_[a] < 1) throw std::invalid_argument("a coarse-graining grid needs at least one cell per axis");
    if (a == 2 && kernel_.dimension == 2 && cells_[a] != 1)
      throw std::invalid_argument("a 2D coarse-graining grid has one cell along z");
    spacing_[a] = box_.length(a) / cells_[a];
  }
  if (!(kernel_.width > 0.0)) throw std::invalid_argument("a coarse-graining kernel needs a positive width");
  sums_.assign(cell_count() * kValues, 0.0);
}

bool CoarseGrainField::spread(const Vec3& x, const double* values, std::size_t offset, std::size_t count) {
  const double reach = kernel_.reach();
  // Per axis, the cells whose centre lies within reach (every periodic image of a cell that does:
  // the range runs past the box and is wrapped) and, for the Gaussian, its factor along that axis
  // (the kernel is their product, 3 exponentials per axis instead of one per cell: its support a
  // cube of 3 widths; the corners it adds beyond the sphere weigh under 1e-3), for Lucy's
  // polynomial the squared distance.
  const bool gaussian = kernel_.kind == CoarseGrainKernel::Kind::gaussian;
  auto& axis_cells = axis_scratch_;
  for (int a = 0; a < 3; ++a) {
    axis_cells[a].clear();
    if (averaged(a)) {  // the coordinate along it is left out
      axis_cells[a].emplace_back(0, gaussian ? 1.0 : 0.0);
      continue;
    }
    const double h = spacing_[a];
    const double u = (x[a] - box_.lo[a]) / h - 0.5;  // in cells, from the first centre
    int first = static_cast<int>(std::ceil(u - reach / h));
    int last = static_cast<int>(std::floor(u + reach / h));
    if (!box_.periodic[a]) {
      first = std::max(first, 0);
      last = std::min(last, cells_[a] - 1);
    }
    for (int i = first; i <= last; ++i) {
      const double d = (i - u) * h;
      if (!(d * d < reach * reach)) continue;
      const int n = cells_[a];
      axis_cells[a].emplace_back(((i % n) + n) % n, gaussian ? kernel_.gaussian_factor(d * d) : d * d);
    }
    if (axis_cells[a].empty()) return false;
  }
  scratch_.clear();
  double total = 0.0;
  for (const auto& [iz, fz] : axis_cells[2])
    for (const auto& [iy, fy] : axis_cells[1])
      for (const auto& [ix, fx] : axis_cells[0]) {
        const double w = gaussian ? fx * fy * fz : kernel_.shape(fx + fy + fz);
        if (w <= 0.0) continue;
        const std::size_t k =
            ix + static_cast<std::size_t>(cells_[0]) * (iy + static_cast<std::size_t>(cells_[1]) * iz);
        scratch_.emplace_back(k, w);
        total += w;
      }
  if (!(total > 0.0)) return false;
  const double scale = 1.0 / (total * cell_volume());
  for (const auto& [k, w] : scratch_) {
    double* cell = &sums_[k * kValues + offset];
    const double f = w * scale;
    for (std::size_t m = 0; m < count; ++m) cell[m] += f * values[m];
  }
  return true;
}

void CoarseGrainField::add_particle(const Vec3& x, double mass, double volume, const Vec3& v) {
  double values[kContact];
  values[kMass] = mass;
  values[kVolume] = volume;
  for (int a = 0; a < 3; ++a) values[kMomentum + a] = mass * v[a];
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) values[kKinetic + kSymmetric[a][b]] = mass * v[a] * v[b];
  if (!spread(x, values, 0, kContact)) lost_mass_ += mass;
}

int CoarseGrainField::branch_points(double length) const {
  // The midpoint rule with points at most half a standard deviation apart: the kernel varies
  // little between them.
  return std::max(1, static_cast<int>(std::ceil(2.0 * length / kernel_.standard_deviation())));
}

void CoarseGrainField::add_contact(const Vec3& x_i, const Vec3& from, const Vec3& force) {
  const Vec3 b = x_i - from;
  const int n = branch_points(norm(b));
  double values[9];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) values[3 * a + c] = b[a] * force[c] / n;
  for (int k = 0; k < n; ++k) spread(from + ((k + 0.5) / n) * b, values, kContact, 9);
}

void CoarseGrainField::clear_sums() {
  std::fill(sums_.begin(), sums_.end(), 0.0);
  lost_mass_ = 0.0;
}

void CoarseGrainField::sum_over_ranks(const RankReduce& ranks) {
  ranks.sum(sums_.data(), sums_.size());
  ranks.sum(&lost_mass_, 1);
}

CoarseGrainCell coarse_grain_cell(const CoarseGrainField& field, std::size_t k) {
  CoarseGrainCell out;
  if (field.samples() == 0) return out;
  const double* s = field.cell_sums(k);
  const double per_sample = 1.0 / static_cast<double>(field.samples());
  out.density = s[CoarseGrainField::kMass] * per_sample;
  out.solid_fraction = s[CoarseGrainField::kVolume] * per_sample;
  for (int a = 0; a < 3; ++a) out.momentum[a] = s[CoarseGrainField::kMomentum + a] * per_sample;
  if (out.density > 0.0) out.velocity = (1.0 / out.density) * out.momentum;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double second = s[CoarseGrainField::kKinetic + kSymmetric[a][b]] * per_sample;
      const double mean = out.density > 0.0 ? out.momentum[a] * out.momentum[b] / out.density : 0.0;
      out.kinetic[3 * a + b] = second - mean;
      out.contact[3 * a + b] = s[CoarseGrainField::kContact + 3 * a + b] * per_sample;
      out.total[3 * a + b] = out.kinetic[3 * a + b] + out.contact[3 * a + b];
    }
  return out;
}

}  // namespace grainflow::observe
