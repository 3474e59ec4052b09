#include "grainflow/dem/domain_decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainflow::dem {

namespace {
// A candidate shape's cost, compared field by field: sub-domains thinner than wanted come after
// all others; then shapes that cut gravity's axis (the material settles along it: a bed poured
// from a height would leave the upper ranks empty), so it is cut only where the others would be
// too thin (a tall silo); then the area of the cut planes (a periodic axis cut p ways has p planes,
// an open or walled one p - 1), equal areas within round-off tying; then how many axes are cut
// (each adds neighbours and messages); last, more cuts along x, then y (so that equal shapes are
// chosen the same way on every machine).
struct ShapeCost {
  bool thin = true;
  double area = std::numeric_limits<double>::infinity();
  int axes = 4;
  bool down_cut = true;
  std::array<int, 3> shape{};
  bool better_than(const ShapeCost& o) const {
    if (thin != o.thin) return !thin;
    if (down_cut != o.down_cut) return !down_cut;
    if (std::fabs(area - o.area) > 1e-9 * std::max(area, o.area)) return area < o.area;
    if (axes != o.axes) return axes < o.axes;
    return shape > o.shape;
  }
};
}  // namespace

std::array<int, 3> DomainDecomposition::choose_shape(int ranks, const std::array<double, 3>& extent,
                                                     const std::array<bool, 3>& periodic, double min_thickness,
                                                     int down) {
  std::array<int, 3> best{ranks, 1, 1};
  ShapeCost best_cost;
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px != 0) continue;
    for (int py = 1; py <= ranks / px; ++py) {
      if ((ranks / px) % py != 0) continue;
      const std::array<int, 3> p{px, py, ranks / px / py};
      ShapeCost cost{false, 0.0, 0, down >= 0 && p[down] > 1, p};
      for (int a = 0; a < 3; ++a) {
        if (p[a] == 1) continue;
        ++cost.axes;
        const double planes = periodic[a] ? p[a] : p[a] - 1;
        cost.area += planes * extent[(a + 1) % 3] * extent[(a + 2) % 3];
        cost.thin = cost.thin || extent[a] / p[a] < min_thickness;
      }
      if (cost.better_than(best_cost)) best = p, best_cost = cost;
    }
  }
  return best;
}

DomainDecomposition DomainDecomposition::balanced(const std::vector<Vec3>& positions, const PeriodicBox& box,
                                                  const Vec3& gravity, int ranks, double ghost_width) {
  DomainDecomposition d;
  d.periodic = box.periodic;
  d.ghost_width = ghost_width;
  int down = -1;
  if (!(gravity == Vec3{})) {
    down = 0;
    for (int a = 1; a < 3; ++a)
      if (std::fabs(gravity[a]) > std::fabs(gravity[down])) down = a;
  }
  // The material's extent: the particles' span inside the box (a bed fills its base, not its height).
  std::array<double, 3> extent{};
  std::array<std::vector<double>, 3> x;
  for (int a = 0; a < 3; ++a) {
    const double lo = box.lo[a], hi = box.hi[a], length = hi - lo;
    x[a].reserve(positions.size());
    for (const Vec3& p : positions) {
      double v = p[a];
      if (box.periodic[a]) v -= length * std::floor((v - lo) / length);
      x[a].push_back(std::clamp(v, lo, hi));
    }
    std::sort(x[a].begin(), x[a].end());
    extent[a] = box.periodic[a] || x[a].empty() ? length : std::max(x[a].back() - x[a].front(), 1e-12 * length);
  }
  // Each cut sub-domain at least two ghost layers thick: thinner ones hold more copies than particles.
  d.shape = choose_shape(ranks, extent, box.periodic, 2.0 * ghost_width, down);
  for (int a = 0; a < 3; ++a) {
    const double lo = box.lo[a], hi = box.hi[a];
    const int p = d.shape[a];
    auto& b = d.bounds[a];
    b.assign(static_cast<std::size_t>(p) + 1, lo);
    b.back() = hi;
    for (int c = 1; c < p; ++c) {
      const std::size_t k = x[a].size() * static_cast<std::size_t>(c) / static_cast<std::size_t>(p);
      const double cut = x[a].empty() ? lo + (hi - lo) * c / p
                                      : (k == 0 ? x[a][0] : 0.5 * (x[a][k - 1] + x[a][std::min(k, x[a].size() - 1)]));
      b[c] = std::clamp(cut, b[c - 1], hi);
    }
  }
  return d;
}

std::array<int, 3> DomainDecomposition::coordinates(int rank) const {
  return {rank % shape[0], (rank / shape[0]) % shape[1], rank / (shape[0] * shape[1])};
}

double DomainDecomposition::wrapped(double v, int axis) const {
  if (!periodic[axis]) return v;
  const double lo = bounds[axis].front(), length = bounds[axis].back() - lo;
  return v - length * std::floor((v - lo) / length);
}

int DomainDecomposition::coordinate(double v, int axis) const {
  const auto& b = bounds[axis];
  const auto it = std::upper_bound(b.begin() + 1, b.end() - 1, wrapped(v, axis));
  return static_cast<int>(it - (b.begin() + 1));
}

int DomainDecomposition::owner(const Vec3& x) const {
  return rank_at({coordinate(x[0], 0), coordinate(x[1], 1), coordinate(x[2], 2)});
}

double DomainDecomposition::axis_gap(double v, int axis, int c) const {
  const auto& b = bounds[axis];
  const double a = b[c], e = b[c + 1];
  auto plain = [&](double u) { return u < a ? a - u : (u >= e ? u - e : 0.0); };
  if (!periodic[axis]) {
    if (c == 0 && v < a) return 0.0;  // beyond the box's ends the end slices reach to infinity
    if (c == shape[axis] - 1 && v >= e) return 0.0;
    return plain(v);
  }
  const double length = b.back() - b.front();
  return std::min({plain(v), plain(v - length), plain(v + length)});
}

double DomainDecomposition::distance_to(const Vec3& x, int r) const {
  const auto c = coordinates(r);
  double squared = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (shape[a] == 1) continue;  // the whole axis
    const double g = axis_gap(x[a], a, c[a]);
    squared += g * g;
  }
  return std::sqrt(squared);
}

std::vector<int> DomainDecomposition::neighbours(int r) const {
  const auto me = coordinates(r);
  std::vector<int> out;
  for (int q = 0; q < ranks(); ++q) {
    if (q == r) continue;
    const auto them = coordinates(q);
    double squared = 0.0;
    for (int a = 0; a < 3; ++a) {
      if (shape[a] == 1) continue;
      // The gap between the two slices along this axis, through the periodic face too.
      const auto& b = bounds[a];
      const double lo1 = b[me[a]], hi1 = b[me[a] + 1], lo2 = b[them[a]], hi2 = b[them[a] + 1];
      auto gap = [&](double shift) { return std::max({lo2 + shift - hi1, lo1 - hi2 - shift, 0.0}); };
      double g = gap(0.0);
      if (periodic[a]) {
        const double length = b.back() - b.front();
        g = std::min({g, gap(length), gap(-length)});
      }
      squared += g * g;
    }
    if (std::sqrt(squared) < ghost_width) out.push_back(q);
  }
  return out;
}

Vec3 DomainDecomposition::lower(int r) const {
  const auto c = coordinates(r);
  return {bounds[0][c[0]], bounds[1][c[1]], bounds[2][c[2]]};
}

Vec3 DomainDecomposition::upper(int r) const {
  const auto c = coordinates(r);
  return {bounds[0][c[0] + 1], bounds[1][c[1] + 1], bounds[2][c[2] + 1]};
}

int DomainDecomposition::bin_of(const Vec3& x, int axis, int bins) const {
  const double lo = bounds[axis].front(), length = bounds[axis].back() - lo;
  return std::clamp(static_cast<int>((wrapped(x[axis], axis) - lo) / length * bins), 0, bins - 1);
}

void DomainDecomposition::rebalance(const std::array<std::vector<double>, 3>& counts) {
  for (int a = 0; a < 3; ++a) {
    if (shape[a] == 1) continue;
    auto& b = bounds[a];
    const double lo = b.front(), length = b.back() - lo;
    const int bins = static_cast<int>(counts[a].size());
    double total = 0.0;
    for (double c : counts[a]) total += c;
    if (!(total > 0.0)) continue;
    double below = 0.0;
    int bin = 0;
    for (int c = 1; c < shape[a]; ++c) {
      const double target = total * c / shape[a];
      while (bin < bins && below + counts[a][bin] < target) below += counts[a][bin++];
      // Within the bin, linearly: the cut where the running count reaches the target.
      const double share = bin < bins && counts[a][bin] > 0.0 ? (target - below) / counts[a][bin] : 0.0;
      b[c] = std::clamp(lo + (bin + share) * length / bins, b[c - 1], b.back());
    }
  }
}

}  // namespace grainflow::dem
