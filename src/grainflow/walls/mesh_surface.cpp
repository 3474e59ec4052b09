#include "grainflow/walls/mesh_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

namespace grainflow::walls {

MeshSurface::MeshSurface(const TriangleMesh& mesh, MeshReport report) : vertices_(mesh.vertices), report_(report) {
  std::map<std::array<std::uint32_t, 2>, std::uint32_t> edge_index;
  const auto edge_of = [&](std::uint32_t p, std::uint32_t q) {
    const std::array<std::uint32_t, 2> key{std::min(p, q), std::max(p, q)};
    const auto [it, added] = edge_index.try_emplace(key, static_cast<std::uint32_t>(edges_.size()));
    if (added) edges_.push_back(key);
    return it->second;
  };
  std::vector<Vec3> box_lo, box_hi;
  facets_.reserve(mesh.triangles.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& [i, j, k] = mesh.triangles[f];
    MeshFacet t;
    t.vertex = {i, j, k};
    t.edge = {edge_of(i, j), edge_of(j, k), edge_of(k, i)};
    t.a = vertices_[i];
    t.ab = vertices_[j] - t.a;
    t.ac = vertices_[k] - t.a;
    const Vec3 n = cross(t.ab, t.ac);
    if (!(norm(n) > 0.0)) throw std::invalid_argument("triangle " + std::to_string(f + 1) + " has zero area");
    t.normal = n * (1.0 / norm(n));
    // Ericson's v for an edge is minus the foot's distance from it times |n| times the edge's length.
    t.edge_scale = {norm(n) * norm(t.ab), norm(n) * norm(vertices_[k] - vertices_[j]), norm(n) * norm(t.ac)};
    t.centre = (1.0 / 3.0) * (vertices_[i] + vertices_[j] + vertices_[k]);
    Vec3 lo = t.a, hi = t.a;
    for (std::uint32_t v : t.vertex) {
      t.bound = std::max(t.bound, norm(vertices_[v] - t.centre));
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], vertices_[v][a]);
        hi[a] = std::max(hi[a], vertices_[v][a]);
      }
    }
    t.bound *= 1.0 + 1e-12;  // the sphere holds the corners despite round-off
    box_lo.push_back(lo);
    box_hi.push_back(hi);
    facets_.push_back(t);
  }
  tree_ = TriangleTree(box_lo, box_hi);
  // Flat features: every triangle around them parallel to the first (either way round).
  constexpr double kFlat = 1e-6;  // rad: float32 coordinates tilt a CAD plane's triangles by ~1e-7
  std::vector<std::int64_t> edge_first(edges_.size(), -1), vertex_first(vertices_.size(), -1);
  flat_edge_.assign(edges_.size(), 0);
  flat_vertex_.assign(vertices_.size(), 1);
  for (std::size_t f = 0; f < facets_.size(); ++f) {
    const MeshFacet& t = facets_[f];
    const auto parallel = [&](std::int64_t g) { return norm(cross(t.normal, facets_[g].normal)) <= kFlat; };
    for (std::uint32_t e : t.edge) {
      if (edge_first[e] < 0) edge_first[e] = static_cast<std::int64_t>(f);
      else flat_edge_[e] = parallel(edge_first[e]);  // an edge of one triangle is a rim: not flat
    }
    for (std::uint32_t v : t.vertex) {
      if (vertex_first[v] < 0) vertex_first[v] = static_cast<std::int64_t>(f);
      else if (!parallel(vertex_first[v])) flat_vertex_[v] = 0;
    }
  }
  for (std::size_t e = 0; e < edges_.size(); ++e)
    if (!flat_edge_[e]) flat_vertex_[edges_[e][0]] = flat_vertex_[edges_[e][1]] = 0;  // a rim's or a ridge's ends
  for (std::size_t f = 0; f < facets_.size(); ++f) {
    MeshFacet& t = facets_[f];
    t.index = static_cast<std::uint32_t>(f);
    for (int k = 0; k < 3; ++k) {
      t.flat_edge[k] = flat_edge_[t.edge[k]];
      t.flat_vertex[k] = flat_vertex_[t.vertex[k]];
    }
  }
}

void MeshSurface::near(const Vec3& x, double reach, std::vector<std::uint32_t>& out) const {
  const std::size_t first = out.size();
  tree_.near(x, reach, [&](std::uint32_t f) {
    if (touch(facets_[f], x).contact.gap < reach) out.push_back(f);
  });
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
}

double MeshSurface::nearest_distance(const Vec3& x, double reach) const {
  double nearest = reach;
  tree_.near(x, reach, [&](std::uint32_t f) { nearest = std::min(nearest, touch(facets_[f], x).contact.gap); });
  return nearest;
}

SurfaceContact MeshSurface::edge_contact(std::uint32_t e, const Vec3& x, const Vec3& fallback) const {
  const Vec3& p = vertices_[edges_[e][0]];
  const Vec3 d = vertices_[edges_[e][1]] - p;
  const double t = std::clamp(dot(x - p, d) / dot(d, d), 0.0, 1.0);
  const Vec3 away = x - (p + t * d);
  const double distance = norm(away);
  if (distance == 0.0) return {0.0, fallback};
  return {distance, away * (1.0 / distance)};
}

SurfaceContact MeshSurface::vertex_contact(std::uint32_t v, const Vec3& x, const Vec3& fallback) const {
  const Vec3 away = x - vertices_[v];
  const double distance = norm(away);
  if (distance == 0.0) return {0.0, fallback};
  return {distance, away * (1.0 / distance)};
}

// The regions of the nearest point as in Ericson, Real-Time Collision Detection (2005), 5.1.5; the
// point itself from the shared edge or vertex, never from this triangle's own corner order.
FacetTouch MeshSurface::touch(const MeshFacet& t, const Vec3& x, bool skip_redundant) const {
  const std::uint32_t f = t.index;
  const Vec3 ap = x - t.a;
  const double h = dot(ap, t.normal);
  const double tolerance = 1e-6 * t.bound;  // x's foot this near a flat edge or vertex is right under it
  const FacetTouch plane{h >= 0.0 ? SurfaceContact{h, t.normal} : SurfaceContact{-h, -t.normal},
                         FacetTouch::Feature::face, f, false};
  const FacetTouch passed_over{{std::numeric_limits<double>::infinity(), t.normal}, FacetTouch::Feature::face, f, true};
  // A flat region's inner vertex or edge: the plane's contact right under x, else passed over
  // (decided from the foot's distance to it, `offset`, before any distance is computed).
  const auto vertex = [&](int k, const Vec3& p) {
    if (t.flat_vertex[k]) {
      if (dot(p, p) - h * h <= tolerance * tolerance) return plane;
      if (skip_redundant) return passed_over;
    }
    FacetTouch touched{vertex_contact(t.vertex[k], x, t.normal), FacetTouch::Feature::vertex, f, false};
    touched.redundant = t.flat_vertex[k] != 0;
    return touched;
  };
  const auto edge = [&](int k, double v) {  // v: minus the foot's distance from the edge, times 2 area x length
    if (t.flat_edge[k]) {
      if (-v <= tolerance * t.edge_scale[k]) return plane;
      if (skip_redundant) return passed_over;
    }
    FacetTouch touched{edge_contact(t.edge[k], x, t.normal), FacetTouch::Feature::edge, f, false};
    touched.redundant = t.flat_edge[k] != 0;
    return touched;
  };
  const double d1 = dot(t.ab, ap), d2 = dot(t.ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return vertex(0, ap);
  const Vec3 bp = ap - t.ab;
  const double d3 = dot(t.ab, bp), d4 = dot(t.ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return vertex(1, bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return edge(0, vc);
  const Vec3 cp = ap - t.ac;
  const double d5 = dot(t.ab, cp), d6 = dot(t.ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return vertex(2, cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return edge(2, vb);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return edge(1, va);
  return plane;
}

bool MeshSurface::joined(const FacetTouch& a, const FacetTouch& b, const Vec3& x, double within) const {
  const MeshFacet& s = facets_[a.facet];
  const MeshFacet& t = facets_[b.facet];
  for (std::uint32_t e : s.edge)
    for (std::uint32_t g : t.edge)
      if (e == g && edge_contact(e, x, s.normal).gap < within) return true;
  for (std::uint32_t v : s.vertex)
    for (std::uint32_t w : t.vertex)
      if (v == w && vertex_contact(v, x, s.normal).gap < within) return true;
  return false;
}

int MeshSurface::contacts(const Vec3& x, double within, const MeshFacet* candidates, std::size_t count,
                          SurfaceContact* out) const {
  std::array<FacetTouch, kMaxTouches> touches;
  int n = 0;
  const double screen2 = within * within * (1.0 + 1e-9);  // the screens' round-off never hides a touch
  for (std::size_t k = 0; k < count && n < kMaxTouches; ++k) {
    // The sphere cuts the triangle's plane in a disc of radius sqrt(within^2 - h^2) about x's
    // foot: the triangle must reach into it (its circumscribing circle, in the plane, at least):
    // |foot - centre| < sqrt(across) + bound, squared twice so that no root is taken.
    const MeshFacet& t = candidates[k];
    const double h = dot(x - t.a, t.normal);
    const double across = screen2 - h * h;
    if (across <= 0.0) continue;
    const Vec3 d = x - t.centre;
    const double dn = dot(d, t.normal);
    const double beyond = dot(d, d) - dn * dn - across - t.bound * t.bound;
    if (beyond > 0.0 && beyond * beyond >= 4.0 * t.bound * t.bound * across) continue;
    const FacetTouch touched = touch(t, x, true);
    if (touched.contact.gap < within && !touched.redundant) touches[n++] = touched;
  }
  if (n <= 1) {
    if (n == 1) out[0] = touches[0].contact;
    return n;
  }
  // Patches: touches joined through a shared edge or vertex within the sphere.
  std::array<int, kMaxTouches> patch;
  std::iota(patch.begin(), patch.begin() + n, 0);
  const auto root = [&](int i) {
    while (patch[i] != i) i = patch[i] = patch[patch[i]];
    return i;
  };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (root(i) != root(j) && joined(touches[i], touches[j], x, within)) patch[root(j)] = root(i);
  std::array<SurfaceContact, kMaxTouches> found;
  int m = 0;
  const double same = 1e-6 * within;  // two face touches this close are one point (see the rule)
  for (int r = 0; r < n; ++r) {
    if (root(r) != r) continue;
    int nearest = -1;
    bool faces = false;
    for (int i = 0; i < n; ++i) {
      if (root(i) != r) continue;
      if (touches[i].feature != FacetTouch::Feature::face) {
        if (nearest < 0 || touches[i].contact.gap < touches[nearest].contact.gap) nearest = i;
        continue;
      }
      faces = true;
      const SurfaceContact& c = touches[i].contact;
      const Vec3 point = x - c.gap * c.normal;
      bool repeated = false;
      for (int q = 0; q < m && !repeated; ++q) repeated = norm(point - (x - found[q].gap * found[q].normal)) <= same;
      if (!repeated) found[m++] = c;
    }
    if (!faces) found[m++] = touches[nearest].contact;
  }
  std::stable_sort(found.begin(), found.begin() + m,
                   [](const SurfaceContact& a, const SurfaceContact& b) { return a.gap < b.gap; });
  m = std::min(m, kMaxContacts);
  std::copy(found.begin(), found.begin() + m, out);
  return m;
}

}  // namespace grainflow::walls
