// Coarse-grained continuum fields of a particle system, the method of Goldhirsch (2010) and
// Weinhart et al. (2012) that MercuryCG implements: with a kernel phi of a chosen width,
//   density            rho(r)   = sum_i m_i phi(r - x_i)
//   momentum density   p(r)     = sum_i m_i v_i phi(r - x_i)
//   kinetic stress     s^k(r)   = sum_i m_i v'_i v'_i phi(r - x_i),  v' = v_i - p / rho
//   contact stress     s^c_ab(r) = sum_c b_a f_b  int_0^1 phi(r - x_i + s b) ds
// with b the branch vector of a contact (from the partner's centre, or the contact point on a wall,
// to x_i) and f the force on i: compressive normal stresses positive, the first index the branch
// direction (the convention of stresses.csv). Fields are sampled at the centres of a regular grid of
// cells over the box and time-averaged; the kinetic stress of the averages is
// <sum m v v phi> - <p><p> / <rho>, the fluctuations about the local time-mean velocity.
//
// The kernel is normalized over the grid's cells each time it spreads a point (a particle, or a
// point of a branch vector's quadrature), so the fields integrate over the cells to the particle
// totals exactly: sum rho dV = sum m, sum p dV = sum m v, sum s^c dV = sum b f (the contact virial),
// on any grid and next to walls, where the kernel is renormalized inside the box (the boundary
// treatment of Weinhart et al.). Periodic axes wrap the kernel, every image counted. A periodic
// axis of one cell is averaged over: the kernel spreads along the other axes only (MercuryCG's
// lower-dimensional coarse graining, e.g. profiles across a chute). In 2D (discs) z is such an
// axis, of one cell, and the fields are per unit area (density kg/m^2, stresses N/m). Each MPI rank
// adds its own particles and the contacts it lists; the sums are added over the ranks.
#pragma once

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"
#include "grainflow/observe/rank_reduce.hpp"

namespace grainflow::observe {

// The kernel's shape: a Gaussian of standard deviation `width` cut off at 3 widths and shifted
// down by its value there (e^-4.5 = 1.1 % of the peak) so that it vanishes continuously (on the
// grid, along each axis: the product of its 1D factors), or Lucy's polynomial (1 + 3q)(1 - q)^3,
// q = r / cutoff, with compact support (Lucy 1977).
struct CoarseGrainKernel {
  enum class Kind { gaussian, lucy };
  Kind kind = Kind::gaussian;
  double width = 0.0;  // m: the Gaussian's standard deviation, or Lucy's cutoff radius
  int dimension = 3;   // 2: it spreads over the x-y plane (discs), fields per unit area

  static constexpr double kGaussianCutoff = 3.0;  // widths
  double reach() const { return kind == Kind::gaussian ? kGaussianCutoff * width : width; }
  // The kernel's value at squared distance r2, up to its normalization (the grid normalizes it).
  double shape(double r2) const;
  // The Gaussian's factor along one axis at squared distance d2 (the grid multiplies three).
  double gaussian_factor(double d2) const;
  // The standard deviation of one coordinate under the kernel (the Gaussian's untruncated; Lucy's
  // c / sqrt(12)): what to compare two kernels' resolutions by.
  double standard_deviation() const;
};

class CoarseGrainField {
 public:
  // Per cell: mass, solid volume, momentum (3), sum m v_a v_b (6: xx yy zz xy xz yz), contact b_a f_b (9).
  static constexpr std::size_t kMass = 0, kVolume = 1, kMomentum = 2, kKinetic = 5, kContact = 11, kValues = 20;

  CoarseGrainField(const PeriodicBox& box, std::array<int, 3> cells, CoarseGrainKernel kernel);

  // One particle at x (any image: the grid wraps it on periodic axes).
  void add_particle(const Vec3& x, double mass, double volume, const Vec3& velocity);
  // One contact: the force on the particle at x_i from a partner at `from` (its image nearest
  // x_i) or from a wall's contact point; the branch b = x_i - from is spread along its length.
  void add_contact(const Vec3& x_i, const Vec3& from, const Vec3& force);
  // The point samples so far become one time sample: the averages count it.
  void close_sample() { ++samples_; }
  void clear_sums();
  // Every rank's sums added (collective): each rank then holds the whole box's.
  void sum_over_ranks(const RankReduce& ranks);

  long samples() const { return samples_; }
  const std::array<int, 3>& cells() const { return cells_; }
  bool averaged(int axis) const {
    return cells_[axis] == 1 && (box_.periodic[axis] || (axis == 2 && kernel_.dimension == 2));
  }
  std::size_t cell_count() const { return static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2]; }
  Vec3 spacing() const { return spacing_; }
  Vec3 origin() const { return box_.lo; }
  // m^3, or m^2 in 2D (the cell's area)
  double cell_volume() const { return spacing_[0] * spacing_[1] * (kernel_.dimension == 2 ? 1.0 : spacing_[2]); }
  const CoarseGrainKernel& kernel() const { return kernel_; }
  // The summed values of cell k (x fastest), kValues of them, per cell volume: sums over samples.
  const double* cell_sums(std::size_t k) const { return &sums_[k * kValues]; }
  const std::vector<double>& sums() const { return sums_; }
  // Mass or contact points whose kernel reached no cell (outside the box on a non-periodic axis).
  double lost_mass() const { return lost_mass_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(sums_, samples_, lost_mass_);
  }

 private:
  // Adds `values` (count of them, from `offset`) to every cell the kernel at x reaches, with the
  // kernel's normalized weight divided by the cell volume; false when it reaches no cell.
  bool spread(const Vec3& x, const double* values, std::size_t offset, std::size_t count);
  // The quadrature points of a branch vector of length `length`.
  int branch_points(double length) const;

  PeriodicBox box_;
  std::array<int, 3> cells_;
  CoarseGrainKernel kernel_;
  Vec3 spacing_;
  std::vector<double> sums_;
  long samples_ = 0;
  double lost_mass_ = 0.0;
  std::vector<std::pair<std::size_t, double>> scratch_;  // the cells of one spread and their weights
  std::array<std::vector<std::pair<int, double>>, 3>
      axis_scratch_;  // per axis: cell, Gaussian factor or squared distance
};

// The time-averaged fields of one cell.
struct CoarseGrainCell {
  double density = 0.0;                                 // kg/m^3
  double solid_fraction = 0.0;                          // solid volume per volume
  Vec3 momentum;                                        // kg/(m^2 s)
  Vec3 velocity;                                        // m/s, momentum / density (0 where no mass reaches)
  std::array<double, 9> kinetic{}, contact{}, total{};  // Pa, row-major (xx, xy, xz, yx, ...)
};
CoarseGrainCell coarse_grain_cell(const CoarseGrainField& field, std::size_t k);

}  // namespace grainflow::observe
