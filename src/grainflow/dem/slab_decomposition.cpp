#include "grainflow/dem/slab_decomposition.hpp"

#include <algorithm>
#include <cmath>

namespace grainflow::dem {

SlabDecomposition SlabDecomposition::balanced(const std::vector<Vec3>& positions, const PeriodicBox& box,
                                              const Vec3& gravity, int ranks, double ghost_width) {
  SlabDecomposition d;
  int down = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(gravity[a]) > std::fabs(gravity[down])) down = a;
  double longest = -1.0;
  for (int a = 0; a < 3; ++a)
    if ((a != down || gravity == Vec3{}) && box.length(a) > longest * (1.0 + 1e-12)) d.axis = a, longest = box.length(a);
  d.periodic = box.periodic[d.axis];
  d.ghost_width = ghost_width;
  const double lo = box.lo[d.axis], hi = box.hi[d.axis];
  std::vector<double> x;
  x.reserve(positions.size());
  for (const Vec3& p : positions) {
    double v = p[d.axis];
    if (d.periodic) v -= box.length(d.axis) * std::floor((v - lo) / box.length(d.axis));
    x.push_back(std::clamp(v, lo, hi));
  }
  std::sort(x.begin(), x.end());
  d.bounds.assign(static_cast<std::size_t>(ranks) + 1, lo);
  d.bounds.back() = hi;
  for (int r = 1; r < ranks; ++r) {
    const std::size_t k = x.size() * static_cast<std::size_t>(r) / static_cast<std::size_t>(ranks);
    const double cut = x.empty() ? lo + (hi - lo) * r / ranks : (k == 0 ? x[0] : 0.5 * (x[k - 1] + x[std::min(k, x.size() - 1)]));
    d.bounds[r] = std::clamp(cut, d.bounds[r - 1], hi);
  }
  return d;
}

int SlabDecomposition::bin_of(const Vec3& x, int bins) const {
  const double lo = bounds.front(), length = bounds.back() - bounds.front();
  double v = x[axis];
  if (periodic) v -= length * std::floor((v - lo) / length);
  return std::clamp(static_cast<int>((v - lo) / length * bins), 0, bins - 1);
}

void SlabDecomposition::rebalance(const std::vector<double>& counts) {
  const double lo = bounds.front(), length = bounds.back() - bounds.front();
  const int bins = static_cast<int>(counts.size());
  double total = 0.0;
  for (double c : counts) total += c;
  if (!(total > 0.0)) return;
  double below = 0.0;
  int b = 0;
  for (int r = 1; r < ranks(); ++r) {
    const double target = total * r / ranks();
    while (b < bins && below + counts[b] < target) below += counts[b++];
    // Within bin b, linearly: the cut where the running count reaches the target.
    const double share = b < bins && counts[b] > 0.0 ? (target - below) / counts[b] : 0.0;
    bounds[r] = std::clamp(lo + (b + share) * length / bins, bounds[r - 1], bounds.back());
  }
}

int SlabDecomposition::owner(const Vec3& x) const {
  double v = x[axis];
  const double lo = bounds.front(), length = bounds.back() - bounds.front();
  if (periodic) v -= length * std::floor((v - lo) / length);
  const auto it = std::upper_bound(bounds.begin() + 1, bounds.end() - 1, v);
  return static_cast<int>(it - (bounds.begin() + 1));
}

double SlabDecomposition::distance_to(const Vec3& x, int r) const {
  const double a = bounds[r], b = bounds[r + 1], v = x[axis];
  auto plain = [&](double u) { return u < a ? a - u : (u >= b ? u - b : 0.0); };
  if (!periodic) {
    // Beyond the box's ends the end slabs reach to infinity.
    if (r == 0 && v < a) return 0.0;
    if (r == ranks() - 1 && v >= b) return 0.0;
    return plain(v);
  }
  const double length = bounds.back() - bounds.front();
  return std::min({plain(v), plain(v - length), plain(v + length)});
}

}  // namespace grainflow::dem
