// A triangle mesh as a contact surface: the exact distance from a sphere's centre to each triangle,
// split into the triangle's face, edge and vertex regions, and the rule that turns a sphere's
// touches of several triangles into its contacts with the surface.
//
// The rule. The triangles a sphere touches fall into patches: two touching triangles belong to one
// patch when they share an edge or a vertex that lies within the sphere. In a patch every touch of a
// triangle's face is a contact (a sphere in a concave groove or corner presses on each face); a
// touch of an edge or a vertex there is not (the faces beside it already push). A patch whose
// touches are all edges or vertices (a convex ridge or corner: every triangle's nearest point is
// the shared edge or vertex) is one contact, at its nearest point. An edge or vertex inside a flat
// region (its triangles coplanar, to 1e-6 rad: float STL files) is no ridge: a centre right above
// it touches the plane there, as a face, and elsewhere it is passed over (the face under the
// centre, or the region's rim, is nearer in the same patch). Two face touches at the same point (1e-6 of the reach
// apart, a flat region's shared edge seen from both sides) are one. So a sphere on a tessellated
// plane feels one contact wherever it is, exactly the plane's, and one crossing a ridge is pushed
// once, not once per triangle. Edge and vertex distances are computed from the shared corners in
// one order, so every triangle sharing them gives the same numbers to the last bit.
//
// Known limit: a sphere pressing on a face and, within the same patch, on a separate convex edge
// (a ledge whose foot lies inside the sphere: deep overlaps only) feels the face alone.
//
// Contacts are two-sided (the normal points from the surface towards the centre, on whichever side
// the centre lies): a mesh may be an open sheet (a blade, a chute) as well as a closed solid.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "grainflow/walls/stl_file.hpp"
#include "grainflow/walls/surface_contact.hpp"
#include "grainflow/walls/triangle_tree.hpp"

namespace grainflow::walls {

// One triangle, ready for contacts.
struct MeshFacet {
  Vec3 a, ab, ac;                                          // corner a and the edges to b and c
  Vec3 normal;                                             // unit, (b - a) x (c - a): the front
  Vec3 centre;                                             // of a sphere around the triangle: a quick test of reach
  double bound = 0.0;                                      // radius of that sphere
  std::array<double, 3> edge_scale{};                      // |(b - a) x (c - a)| times the length of edge ab, bc, ca
  std::array<std::uint32_t, 3> vertex;                     // welded corners a, b, c
  std::array<std::uint32_t, 3> edge;                       // edges ab, bc, ca: indices into MeshSurface::edges
  std::uint32_t index = 0;                                 // its number in the surface
  std::array<std::uint8_t, 3> flat_edge{}, flat_vertex{};  // inside a flat region (below)
};

// Where a sphere touches one triangle: the surface contact and the feature (face, edge, vertex) the
// nearest point lies on.
struct FacetTouch {
  enum class Feature : std::uint8_t { face, edge, vertex };
  SurfaceContact contact;
  Feature feature = Feature::face;
  std::uint32_t facet = 0;
  // A flat region's inner edge or vertex, not right under the centre: never a contact of its own
  // (the face under the centre, or the region's rim, is nearer in the same patch).
  bool redundant = false;
};

class MeshSurface {
 public:
  // At most this many contacts per sphere and mesh: a sphere in a corner where three faces meet
  // presses on three; the deepest ones are kept if ever more (the engine keeps this many histories).
  static constexpr int kMaxContacts = 4;
  // More triangles than this touching one sphere are not examined (a mesh far finer than the grains).
  static constexpr int kMaxTouches = 64;

  MeshSurface() = default;
  // From a checked mesh (check_mesh, whose findings `report` keeps); throws std::invalid_argument
  // for a degenerate triangle.
  explicit MeshSurface(const TriangleMesh& mesh, MeshReport report = {});
  const MeshReport& report() const { return report_; }

  std::size_t size() const { return facets_.size(); }
  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<MeshFacet>& facets() const { return facets_; }
  const Vec3& lo() const { return tree_.lo(); }
  const Vec3& hi() const { return tree_.hi(); }

  // The triangles within `reach` of x (their nearest point, not only their box), ascending.
  void near(const Vec3& x, double reach, std::vector<std::uint32_t>& out) const;
  // The distance from x to the nearest triangle, or `reach` when none is nearer.
  double nearest_distance(const Vec3& x, double reach) const;
  // Where x lies against triangle t: the nearest point's feature and the two-sided contact.
  // `skip_redundant`: a touch marked redundant is not measured (its gap is infinite).
  FacetTouch touch(const MeshFacet& t, const Vec3& x, bool skip_redundant = false) const;
  FacetTouch touch(std::uint32_t f, const Vec3& x) const { return touch(facets_[f], x); }
  // The contacts of a sphere centred at x with the surface, among the triangles `candidates`
  // (copies of those that may come within `within` of x, laid out in the order a step reads them:
  // a step then streams through memory instead of jumping about the mesh), by the rule above:
  // those nearer than `within`, deepest first. Returns how many were written to `out` (at most
  // kMaxContacts).
  int contacts(const Vec3& x, double within, const MeshFacet* candidates, std::size_t count, SurfaceContact* out) const;

 private:
  SurfaceContact edge_contact(std::uint32_t e, const Vec3& x, const Vec3& fallback) const;
  SurfaceContact vertex_contact(std::uint32_t v, const Vec3& x, const Vec3& fallback) const;
  bool joined(const FacetTouch& a, const FacetTouch& b, const Vec3& x, double within) const;

  std::vector<Vec3> vertices_;
  std::vector<std::array<std::uint32_t, 2>> edges_;    // the lower vertex index first
  std::vector<std::uint8_t> flat_edge_, flat_vertex_;  // inside a flat region: its triangles coplanar
  std::vector<MeshFacet> facets_;
  TriangleTree tree_;
  MeshReport report_;
};

}  // namespace grainflow::walls
