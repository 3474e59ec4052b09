// Mesh walls (type = "mesh"): the surface's contact rule on shapes whose answer geometry gives
// exactly (a tessellated plane, a ridge, a groove, a box's corners), a sphere on a tessellated plane
// moving as on the analytic plane, a sphere resting in a V-groove on both faces, a bed in a faceted
// cylinder approaching the analytic cylinder as the facets get finer, and bad input refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numeric>
#include <sstream>
#include <string>
#include <variant>

#include "grainflow/core/error.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/walls/mesh_surface.hpp"
#include "grainflow/walls/stl_file.hpp"
#include "sphere_path.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::walls;

namespace {

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::path(testing::TempDir()) / ("grainflow_mesh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

// A rectangle [x0, x1] x [z0, z1] in the plane y = 0, nx by nz cells of two triangles (diagonals
// alternating), its interior vertices moved within the plane by up to `jitter` of a cell
// (deterministically), so that a sphere meets edges and vertices at every angle.
TriangleMesh tessellated_plane(double x0, double x1, double z0, double z1, int nx, int nz, double jitter) {
  TriangleMesh m;
  const double dx = (x1 - x0) / nx, dz = (z1 - z0) / nz;
  std::uint64_t seed = 12345;
  auto uniform = [&]() {  // in [-1, 1)
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) / 4503599627370496.0 - 1.0;
  };
  for (int i = 0; i <= nx; ++i)
    for (int k = 0; k <= nz; ++k) {
      Vec3 v{x0 + i * dx, 0.0, z0 + k * dz};
      if (i > 0 && i < nx && k > 0 && k < nz) v.x += jitter * dx * uniform(), v.z += jitter * dz * uniform();
      m.vertices.push_back(v);
    }
  auto at = [&](int i, int k) { return static_cast<std::uint32_t>(i * (nz + 1) + k); };
  for (int i = 0; i < nx; ++i)
    for (int k = 0; k < nz; ++k) {
      const auto a = at(i, k), b = at(i + 1, k), c = at(i + 1, k + 1), d = at(i, k + 1);
      if ((i + k) % 2 == 0) {
        m.triangles.push_back({a, d, c});  // front +y
        m.triangles.push_back({a, c, b});
      } else {
        m.triangles.push_back({a, d, b});
        m.triangles.push_back({b, d, c});
      }
    }
  return m;
}

// Every point above a tessellated plane, above a face, an edge or a vertex, has one contact: the
// plane's, gap = y exactly and normal +y (round-off only where the nearest point is an edge's or a
// vertex's, whose direction carries ~1e-16 of in-plane residue).
TEST(MeshSurface, ATessellatedPlaneGivesThePlanesContactEverywhere) {
  const MeshSurface surface(tessellated_plane(-1.0, 1.0, -1.0, 1.0, 8, 8, 0.3));
  std::vector<Vec3> points;
  for (const Vec3& v : surface.vertices()) points.push_back(v + Vec3{0.0, 0.09, 0.0});  // over each vertex
  for (const MeshFacet& f : surface.facets()) {
    points.push_back(f.a + 0.5 * f.ab + Vec3{0.0, 0.07, 0.0});  // over each edge's midpoint
    points.push_back(f.centre + Vec3{0.0, 0.05, 0.0});
    points.push_back(f.a + 0.999 * f.ab + 0.0005 * f.ac + Vec3{0.0, 0.08, 0.0});  // near a corner
  }
  int checked = 0;
  for (const Vec3& x : points) {
    if (std::fabs(x.x) > 0.8 || std::fabs(x.z) > 0.8) continue;  // away from the rectangle's rim
    std::array<SurfaceContact, MeshSurface::kMaxContacts> out;
    const int n = surface.contacts(x, 0.1, surface.facets().data(), surface.size(), out.data());
    ASSERT_EQ(n, 1) << "at (" << x.x << ", " << x.y << ", " << x.z << ")";
    EXPECT_NEAR(out[0].gap, x.y, 1e-15);
    EXPECT_NEAR(out[0].normal.y, 1.0, 1e-15);
    EXPECT_NEAR(std::hypot(out[0].normal.x, out[0].normal.z), 0.0, 1e-14);
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

// A roof: two triangles strips meeting along the ridge x = 0 at height 1, falling at 30 degrees.
// Over the ridge the nearest point of both sides is the ridge itself: one contact, from the ridge.
// In the mirrored V-groove a sphere on the bisector presses on both faces, each along its normal.
TEST(MeshSurface, ARidgePushesOnceAndAGrooveTwice) {
  const double slope = std::tan(M_PI / 6.0);
  for (const double sign : {-1.0, 1.0}) {  // -1: a roof (ridge up), +1: a groove
    TriangleMesh m;
    m.vertices = {{-1.0, sign * slope, -1.0}, {0.0, 0.0, -1.0}, {1.0, sign * slope, -1.0},
                  {-1.0, sign * slope, 1.0},  {0.0, 0.0, 1.0},  {1.0, sign * slope, 1.0}};
    m.triangles = {{0, 3, 4}, {0, 4, 1}, {1, 4, 5}, {1, 5, 2}};
    const MeshSurface surface(m);
    std::array<SurfaceContact, MeshSurface::kMaxContacts> out;
    const Vec3 x{0.0, 0.5, 0.1};
    const int n = surface.contacts(x, 1.0, surface.facets().data(), surface.size(), out.data());
    if (sign < 0.0) {
      ASSERT_EQ(n, 1);
      EXPECT_DOUBLE_EQ(out[0].gap, 0.5);
      EXPECT_NEAR(norm(out[0].normal - Vec3{0.0, 1.0, 0.0}), 0.0, 1e-15);
    } else {
      ASSERT_EQ(n, 2);
      // The distance from (0, 0.5) to a line through the origin at 30 degrees: 0.5 cos 30.
      for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(out[k].gap, 0.5 * std::cos(M_PI / 6.0), 1e-15);
        EXPECT_NEAR(out[k].normal.y, std::cos(M_PI / 6.0), 1e-15);
        EXPECT_NEAR(std::fabs(out[k].normal.x), std::sin(M_PI / 6.0), 1e-15);
      }
      EXPECT_NEAR(out[0].normal.x + out[1].normal.x, 0.0, 1e-15);  // one on each face
    }
  }
}

// A closed unit cube of 12 triangles (two per face, the diagonals making every corner a vertex of
// several triangles). Inside, a sphere in a corner presses on the three faces; outside, a sphere
// beyond a corner touches only that vertex: one contact, along the diagonal.
TEST(MeshSurface, ACubesCornerIsThreeFacesInsideAndOneVertexOutside) {
  TriangleMesh cube;
  for (int k = 0; k < 8; ++k) cube.vertices.push_back({double(k & 1), double(k >> 1 & 1), double(k >> 2 & 1)});
  const std::array<std::array<std::uint32_t, 4>, 6> faces{
      {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  for (const auto& f : faces) {
    cube.triangles.push_back({f[0], f[1], f[2]});
    cube.triangles.push_back({f[0], f[2], f[3]});
  }
  const MeshSurface surface(cube);
  std::array<SurfaceContact, MeshSurface::kMaxContacts> out;
  int n = surface.contacts({0.1, 0.1, 0.1}, 0.15, surface.facets().data(), surface.size(), out.data());
  ASSERT_EQ(n, 3);
  Vec3 sum;
  for (int k = 0; k < n; ++k) {
    EXPECT_NEAR(out[k].gap, 0.1, 1e-15);
    sum += out[k].normal;
  }
  EXPECT_NEAR(norm(sum - Vec3{1.0, 1.0, 1.0}), 0.0, 1e-15);
  const double d = 0.05;
  n = surface.contacts({1.0 + d, 1.0 + d, 1.0 + d}, 0.1, surface.facets().data(), surface.size(), out.data());
  ASSERT_EQ(n, 1);
  EXPECT_NEAR(out[0].gap, std::sqrt(3.0) * d, 1e-15);
  EXPECT_NEAR(norm(out[0].normal - Vec3{1.0, 1.0, 1.0} * (1.0 / std::sqrt(3.0))), 0.0, 1e-15);
  // Beyond an edge's middle: the edge, once, though two triangles of each of two faces meet there.
  n = surface.contacts({0.5, 1.0 + d, 1.0 + d}, 0.1, surface.facets().data(), surface.size(), out.data());
  ASSERT_EQ(n, 1);
  EXPECT_NEAR(out[0].gap, std::sqrt(2.0) * d, 1e-15);
}

// The tree finds what a search of every triangle finds.
TEST(MeshSurface, TheTreeFindsEveryTriangleWithinReach) {
  const MeshSurface surface(tessellated_plane(-1.0, 1.0, -1.0, 1.0, 20, 20, 0.3));
  for (const Vec3& x : {Vec3{0.1, 0.05, 0.2}, Vec3{-0.93, -0.02, 0.5}, Vec3{1.05, 0.0, 0.0}, Vec3{0.0, 0.3, 0.0}}) {
    std::vector<std::uint32_t> found;
    surface.near(x, 0.12, found);
    std::vector<std::uint32_t> every;
    for (std::uint32_t f = 0; f < surface.size(); ++f)
      if (surface.touch(f, x).contact.gap < 0.12) every.push_back(f);
    EXPECT_EQ(found, every);
  }
}

}  // namespace

namespace {

constexpr double kG = 9.81, kTheta = 0.35;  // rad, ~20 degrees
constexpr double kDiameter = 0.002;

using test::law_keys;
using test::Motion3;
using test::species_keys;
using test::wall_keys;

// One sphere released 0.3 d above the plane y = 0 under gravity tilted by theta along x, thrown
// across it with spin: it bounces, slides, then rolls ~2.5 cm in 0.04 s, over some 20 triangles of
// 0.6 d (jittered: edges and vertices at every angle) when the plane is a mesh.
std::vector<Motion3> run_on_plane(std::string_view law, const std::string& plane_keys, int steps,
                                  const std::string& motion = "") {
  std::ostringstream row, t;
  row.precision(17);
  row << "glass,-0.01," << 1.3 * 0.5 * kDiameter << ",0.0,0.5,-0.1,0.2,0.0,0.0,-20.0\n";
  const test::ParticleFile csv("sphere.csv", row.str(), "species,x,y,z,vx,vy,vz,wx,wy,wz");
  t.precision(17);
  t << "[domain]\nlo = [-0.03, -0.01, -0.03]\nhi = [0.03, 0.03, 0.03]\n"
    << "boundary = { x = \"open\", y = \"open\", z = \"open\" }\n"
    << "[gravity]\nvector = [" << kG * std::sin(kTheta) << ", " << -kG * std::cos(kTheta) << ", 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = " << kDiameter << "\ndensity = 2500.0\n" << species_keys(law)
    << "[particles]\ninit = \"file\"\nfile = \"" << csv.path() << "\"\n[contact]\n" << law_keys(law)
    << "[[geometry]]\nname = \"floor\"\n" << plane_keys << wall_keys(law) << motion
    << "[run]\nduration = 1.0\ntime_step = 2.0e-6\n";
  auto engine = test::engine_from_toml(t.str(), testing::TempDir() + "mesh_plane.toml", 1);
  std::vector<Motion3> path;
  std::visit(
      [&](auto& e) {
        const auto& p = e.state().particles;
        for (int k = 0; k < steps; ++k) {
          e.step();
          if (k % 100 == 99) path.push_back({p.position[0], p.velocity[0], p.angular_velocity[0]});
        }
      },
      engine);
  return path;
}

// On a face of the mesh the contact is the plane's to the last bit (the triangles' normal is +y
// exactly and gap = y exactly); where the centre is right above an edge or a vertex, the flat
// region's rule gives the plane's contact too. The two engines' loops are compiled apart, so their
// floating-point contractions may differ in the last bit; summed over the steps that stays near
// 1e-13 m. A second contact counted at an edge for one step would change the velocity by ~1e-4 m/s
// and the path by >= 1e-8 m. As for the tilted plane (test_geometry_walls): 1e-11 m, 1e-8 m/s and
// 1e-5 rad/s (of ~20 rad/s).
TEST(MeshWalls, ASphereOnATessellatedPlaneMovesAsOnThePlaneForEveryLaw) {
  const std::string stl = temp_path("floor.stl");
  write_stl(tessellated_plane(-0.03, 0.03, -0.03, 0.03, 50, 50, 0.3), stl, true);
  dem::for_each_contact_law([&]<dem::ContactLaw Law>() {
    const auto plane = run_on_plane(Law::name, "type = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n", 20000);
    const auto mesh = run_on_plane(Law::name, "type = \"mesh\"\nfile = \"" + stl + "\"\n", 20000);
    ASSERT_EQ(plane.size(), mesh.size());
    const auto [dx, dv, dw] = test::largest_differences(plane, mesh);
    EXPECT_LE(dx, 1e-11) << Law::name;
    EXPECT_LE(dv, 1e-8) << Law::name;
    EXPECT_LE(dw, 1e-5) << Law::name;
    EXPECT_GT(norm(mesh.back().x - mesh.front().x), 15 * 0.0012) << Law::name << ": it should cross ~20 triangles";
  });
}

// A moving mesh carries its pose: the tessellated plane turning about its normal (a turntable at
// 20 rad/s, which drags the sphere round) or rising along it at 1 cm/s moves the sphere as the
// analytic plane does, whose surface stays where it is (turning) or moves by the same shift. The
// mesh's triangles are turned and the centre taken back into their frame, which rounds differently
// from the plane's own arithmetic: the tolerances of the still plane's test.
TEST(MeshWalls, ATurningOrRisingMeshMovesTheSphereAsThePlaneDoes) {
  const std::string stl = temp_path("floor_moving.stl");
  write_stl(tessellated_plane(-0.03, 0.03, -0.03, 0.03, 50, 50, 0.3), stl, true);
  for (const std::string motion : {"[geometry.motion]\nangular_velocity = [0.0, 20.0, 0.0]\n",
                                   "[geometry.motion]\nvelocity = [0.0, 0.01, 0.0]\n"}) {
    const auto plane = run_on_plane("linear_dashpot",
                                    "type = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n", 20000, motion);
    const auto mesh = run_on_plane("linear_dashpot", "type = \"mesh\"\nfile = \"" + stl + "\"\n", 20000, motion);
    ASSERT_EQ(plane.size(), mesh.size());
    const auto [dx, dv, dw] = test::largest_differences(plane, mesh);
    EXPECT_LE(dx, 1e-11) << motion;
    EXPECT_LE(dv, 1e-8) << motion;
    EXPECT_LE(dw, 1e-5) << motion;
  }
  // The turntable did drag the sphere (0.6 mm off the still floor's path by 0.04 s): a wall taken as
  // still would leave the two paths 1e-11 m apart.
  const auto still = run_on_plane("linear_dashpot", "type = \"mesh\"\nfile = \"" + stl + "\"\n", 20000);
  const auto turning = run_on_plane("linear_dashpot", "type = \"mesh\"\nfile = \"" + stl + "\"\n", 20000,
                                    "[geometry.motion]\nangular_velocity = [0.0, 20.0, 0.0]\n");
  EXPECT_GT(norm(still.back().x - turning.back().x), 1e-4);
}

// A frictionless sphere dropped off-centre into a V-groove (faces at 45 degrees, meeting along the
// z axis) settles on both faces, its only equilibrium: centred (x = 0), each face pushing
// N = m g / (2 cos 45) along its normal, so its centre lies (r - N / kn) / cos 45 above the groove's
// line, and the groove carries its weight. The damping (gamma_n = 2e4 /s against sqrt(kn / m) =
// 3e4 rad/s) stops each bounce within a contact.
TEST(MeshWalls, ASphereRestsInAVGrooveOnBothFaces) {
  TriangleMesh groove;
  groove.vertices = {{-0.01, 0.01, -0.01}, {0.0, 0.0, -0.01}, {0.01, 0.01, -0.01},
                     {-0.01, 0.01, 0.01},  {0.0, 0.0, 0.01},  {0.01, 0.01, 0.01}};
  groove.triangles = {{0, 3, 4}, {0, 4, 1}, {1, 4, 5}, {1, 5, 2}};
  const std::string stl = temp_path("groove.stl");
  write_stl(groove, stl, false);
  const test::ParticleFile csv("groove.csv", "glass,0.0004,0.003,0.0,0,0,0\n");
  std::ostringstream t;
  t << "[domain]\nlo = [-0.012, -0.001, -0.012]\nhi = [0.012, 0.012, 0.012]\n"
    << "boundary = { x = \"open\", y = \"open\", z = \"open\" }\n[gravity]\nvector = [0.0, -9.81, 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = 0.002\ndensity = 2500.0\n"
    << "[particles]\ninit = \"file\"\nfile = \"" << csv.path() << "\"\n"
    << "[contact]\nmodel = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 2.0e4\nfriction = 0.0\n"
    << "[[geometry]]\nname = \"groove\"\ntype = \"mesh\"\nfile = \"" << stl << "\"\n"
    << "[run]\nduration = 1.0\ntime_step = 2.0e-6\n";
  auto engine = test::engine_from_toml(t.str(), testing::TempDir() + "groove.toml", 1);
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < 150000; ++k) e.step();  // 0.3 s: hundreds of damping times
        const auto& p = e.state().particles;
        const double m = p.mass[0], r = 0.001, c45 = std::sqrt(0.5);
        const double normal = m * 9.81 / (2.0 * c45);
        // At rest to 1e-9 m (the damped swing's remainder); the overlap N / kn is 7e-9 m, so one face
        // alone (the sphere sliding down it) or a doubled contact would be off by far more.
        EXPECT_NEAR(p.position[0].x, 0.0, 1e-9);
        EXPECT_NEAR(p.position[0].y, (r - normal / 1.0e4) / c45, 1e-11);
        EXPECT_EQ(e.statistics().wall_contacts, 2);
        std::size_t w = 0;
        while (e.state().walls[w].name != "groove") ++w;
        const Vec3 load = e.force_on_wall(w);
        EXPECT_NEAR(load.y, -m * 9.81, 1e-6 * m * 9.81);
        EXPECT_NEAR(load.x, 0.0, 1e-6 * m * 9.81);
      },
      engine);
}

}  // namespace

namespace {

// A case with one small bed over a mesh floor from `stl` (with `extra` keys in its table).
std::string mesh_case(const std::string& stl, const std::string& extra = "", bool discs = false) {
  return "[domain]\nlo = [-0.01, 0.0, -0.01]\nhi = [0.01, 0.02, 0.01]\n" +
         std::string(discs ? "boundary = { x = \"open\", y = \"open\", z = \"periodic\" }\n[engine]\ndimension = 2\n"
                           : "boundary = { x = \"open\", y = \"open\", z = \"open\" }\n") +
         "[[species]]\nname = \"glass\"\ndiameter = 0.002\ndensity = 2500.0\ncount = 4\n"
         "[particles]\ninit = \"random\"\nregion_lo = [-0.008, 0.004, -0.008]\nregion_hi = [0.008, 0.015, 0.008]\n"
         "[contact]\nmodel = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 0.05\nfriction = 0.3\n"
         "[[geometry]]\nname = \"tray\"\ntype = \"mesh\"\nfile = \"" +
         stl + "\"\n" + extra + "[run]\nduration = 0.01\ntime_step = 2.0e-6\n";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string refusal(const std::string& text) {
  try {
    auto engine = test::engine_from_toml(text, testing::TempDir() + "bad_mesh.toml", 1);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(MeshWalls, BadMeshesAreRefusedNamingTheFileTheTriangleAndTheReason) {
  const std::string good = temp_path("tray.stl");
  write_stl(tessellated_plane(-0.01, 0.01, -0.01, 0.01, 4, 4, 0.0), good, true);
  EXPECT_EQ(refusal(mesh_case(good)), "(accepted)");

  EXPECT_PRED2(contains, refusal(mesh_case(temp_path("missing.stl"))), "is not a readable file");

  TriangleMesh nan = tessellated_plane(-0.01, 0.01, -0.01, 0.01, 4, 4, 0.0);
  nan.vertices[7].y = std::nan("");
  const std::string nan_file = temp_path("nan.stl");
  write_stl(nan, nan_file, false);
  const std::string nan_message = refusal(mesh_case(nan_file));
  EXPECT_PRED2(contains, nan_message, nan_file);
  EXPECT_PRED2(contains, nan_message, "triangle");
  EXPECT_PRED2(contains, nan_message, "tray");  // the geometry's name

  TriangleMesh flat = tessellated_plane(-0.01, 0.01, -0.01, 0.01, 4, 4, 0.0);
  flat.triangles[5] = {flat.triangles[5][0], flat.triangles[5][1], flat.triangles[5][1]};
  const std::string flat_file = temp_path("degenerate.stl");
  write_stl(flat, flat_file, true);
  EXPECT_PRED2(contains, refusal(mesh_case(flat_file)), "triangle 6");

  // An open tray where a closed solid is asked for.
  EXPECT_PRED2(contains, refusal(mesh_case(good, "closed = true\n")), "closed");

  // Millimetres read as metres: the 20 mm tray becomes 20 m, 10^4 diameters; scaled 1000 times
  // more it is 10^7 diameters. And metres read as millimetres: 20 micrometres.
  EXPECT_EQ(refusal(mesh_case(good, "scale = 1000.0\n")), "(accepted)");  // 20 m: large, not absurd
  EXPECT_PRED2(contains, refusal(mesh_case(good, "scale = 1.0e6\n")), "particle diameters");
  EXPECT_PRED2(contains, refusal(mesh_case(good, "scale = 0.001\n")), "less than one particle diameter");

  EXPECT_PRED2(contains, refusal(mesh_case(good, "scale = -1.0\n")), "scale");
  EXPECT_PRED2(contains, refusal(mesh_case(good, "", true)), "a mesh is a surface in 3D");
}

}  // namespace

namespace {

// A faceted cylinder about z: N facets (chords of the circle of radius R, vertices at 2 pi k / N),
// z from z0 to z1.
TriangleMesh faceted_cylinder(double radius, int facets, double z0, double z1) {
  TriangleMesh m;
  for (int k = 0; k < facets; ++k) {
    const double a = 2.0 * M_PI * k / facets;
    m.vertices.push_back({radius * std::cos(a), radius * std::sin(a), z0});
    m.vertices.push_back({radius * std::cos(a), radius * std::sin(a), z1});
  }
  for (int k = 0; k < facets; ++k) {
    const auto a = static_cast<std::uint32_t>(2 * k), b = static_cast<std::uint32_t>(2 * ((k + 1) % facets));
    m.triangles.push_back({a, b, b + 1});
    m.triangles.push_back({a, b + 1, a + 1});
  }
  return m;
}

// 70 frictional spheres (d = 2 mm) settled for 0.15 s in a horizontal cylinder of radius 5 d,
// periodic along its axis, as the analytic `cylinder` or a mesh of `facets` facets (poured from a
// region inside it: a mesh has no inside, random placement only keeps centres clear of its surface).
// Returns the mean distance from the axis of the spheres within `band` of the wall's inner radius R - r.
double wall_ring_radius(int facets, double band) {
  const double radius = 0.01;
  std::ostringstream t;
  t << "[domain]\nlo = [-0.0105, -0.0105, 0.0]\nhi = [0.0105, 0.0105, 0.006]\n"
    << "boundary = { x = \"open\", y = \"open\", z = \"periodic\" }\n[gravity]\nvector = [0.0, -9.81, 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = 0.002\ndensity = 2500.0\ncount = 70\n"
    << "[particles]\ninit = \"random\"\nregion_lo = [-0.006, -0.006, 0.0]\nregion_hi = [0.006, 0.003, 0.006]\n"
    << "seed = 3\nexpansion_time = 0.01\n"
    << "[contact]\nmodel = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 2.0e4\nfriction = 0.3\n[[geometry]]\nname = \"drum\"\n";
  if (facets == 0) {
    t << "type = \"cylinder\"\npoint = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nradius = " << radius << "\n";
  } else {
    const std::string stl = temp_path("cylinder_" + std::to_string(facets) + ".stl");
    write_stl(faceted_cylinder(radius, facets, -0.004, 0.01), stl, true);
    t << "type = \"mesh\"\nfile = \"" << stl << "\"\n";
  }
  t << "[run]\nduration = 1.0\ntime_step = 2.0e-6\n";
  auto engine = test::engine_from_toml(t.str(), testing::TempDir() + "faceted.toml", 1);
  return std::visit(
      [&](auto& e) {
        for (int k = 0; k < 75000; ++k) e.step();
        const auto& p = e.state().particles;
        double sum = 0.0;
        int n = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
          const double rho = std::hypot(p.position[i].x, p.position[i].y);
          if (rho > radius - p.radius[i] - band) sum += rho, ++n;
        }
        EXPECT_GT(n, 8) << facets << " facets: the bed's outer ring";
        return sum / n;
      },
      engine);
}

// The spheres at the wall of the analytic cylinder sit at R - r (plus their overlap with the wall,
// at most the bed's weight over kn: 7e-7 m).
// A facet's middle lies R (1 - cos(pi / N)) (its sagitta s) nearer the axis and its corners on the
// circle, so a sphere on a facet sits between R cos(pi / N) - r and R - r (in a corner, touching two
// facets, it sits deeper than the middle by at most another ~s): the ring's mean radius falls short
// of the analytic one by a fraction of s, which shrinks as 1 / N^2. We allow the deficit up to 1.5 s
// + 1e-6 m (overlaps), and require it to shrink at least 8-fold from 12 to 48 facets (16-fold in s).
TEST(MeshWalls, ABedInAFacetedCylinderApproachesTheAnalyticCylinder) {
  const double radius = 0.01;
  const auto sagitta = [&](int n) { return radius * (1.0 - std::cos(M_PI / n)); };
  const double band = 0.05 * 0.001;
  const double analytic = wall_ring_radius(0, band + sagitta(12));
  EXPECT_NEAR(analytic, radius - 0.001, 1e-6);
  std::array<double, 3> deficit{};
  const std::array<int, 3> counts{12, 24, 48};
  for (int k = 0; k < 3; ++k) {
    deficit[k] = analytic - wall_ring_radius(counts[k], band + sagitta(counts[k]));
    EXPECT_GE(deficit[k], -1e-6) << counts[k] << " facets";
    EXPECT_LE(deficit[k], 1.5 * sagitta(counts[k]) + 1e-6) << counts[k] << " facets";
    std::cerr << counts[k] << " facets: sagitta " << sagitta(counts[k]) << " m, ring radius short by " << deficit[k]
              << " m\n";
  }
  EXPECT_LT(deficit[2], deficit[0] / 8.0);
}

}  // namespace
