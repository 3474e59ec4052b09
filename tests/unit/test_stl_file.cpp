// STL files: a cube written binary and ASCII and read back (welded corners, exact volume, the
// same bits), a binary header starting with "solid", the winding repaired (some triangles turned,
// the whole cube inside out), an open tessellated square, and each refusal naming its triangle.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "grainflow/core/error.hpp"
#include "grainflow/walls/stl_file.hpp"

using namespace grainflow;
using namespace grainflow::walls;

namespace {

// A closed cube [0, side]^3 facing outwards: on each face, the square p, p+u, p+u+v, p+v walks
// counter-clockwise about u x v = +axis; the face at 0 walks it backwards (facing -axis).
TriangleMesh cube(double side) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back({side * (i & 1), side * (i >> 1 & 1), side * (i >> 2 & 1)});
  for (int axis = 0; axis < 3; ++axis)
    for (int at = 0; at < 2; ++at) {
      const int p = at << axis, u = 1 << (axis + 1) % 3, v = 1 << (axis + 2) % 3;
      std::uint32_t q[4] = {std::uint32_t(p), std::uint32_t(p + u), std::uint32_t(p + u + v), std::uint32_t(p + v)};
      if (at == 0) std::swap(q[1], q[3]);
      m.triangles.push_back({q[0], q[1], q[2]});
      m.triangles.push_back({q[0], q[2], q[3]});
    }
  return m;
}

// The unit square in z = 0 in nx * nx cells, each two triangles, facing +z.
TriangleMesh square(int nx) {
  TriangleMesh m;
  for (int j = 0; j <= nx; ++j)
    for (int i = 0; i <= nx; ++i) m.vertices.push_back({double(i) / nx, double(j) / nx, 0.0});
  for (int j = 0; j < nx; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::uint32_t a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

// The enclosed volume, dividing by 6 once: exact for corners at small multiples of a power of two.
double volume(const TriangleMesh& m) {
  double six_v = 0.0;
  for (const auto& [a, b, c] : m.triangles) six_v += dot(m.vertices[a], cross(m.vertices[b], m.vertices[c]));
  return six_v / 6.0;
}

// Consistent winding: every directed edge is walked once, and an inner edge once each way.
void expect_consistent(const TriangleMesh& m, bool closed) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> walked;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(walked.insert({t[k], t[(k + 1) % 3]}).second);
  if (!closed) return;
  for (const auto& [a, b] : walked) EXPECT_TRUE(walked.count({b, a})) << a << " " << b;
}

class StlFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("grainflow_stl_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::string write_text(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }

  // The reason read_stl and then check_mesh refuse the file (or check_mesh the mesh) with.
  static std::string refusal(const std::string& path, bool must_be_closed = false) {
    try {
      TriangleMesh m = read_stl(path, "walls.file");
      check_mesh(m, path, "walls.file", must_be_closed);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.key(), "walls.file");
      return e.reason();
    }
    ADD_FAILURE() << path << " was accepted";
    return "";
  }
  static std::string refusal(TriangleMesh m) {
    try {
      check_mesh(m, "mem", "k", false);
    } catch (const InputError& e) {
      return e.reason();
    }
    ADD_FAILURE() << "the mesh was accepted";
    return "";
  }

  std::filesystem::path dir_;
};

TEST_F(StlFile, ClosedCubeRoundTripsThroughBinary) {
  write_stl(cube(0.5), file("cube.stl"), true);
  EXPECT_EQ(std::filesystem::file_size(file("cube.stl")), 84u + 50u * 12u);
  MeshReport read;
  TriangleMesh m = read_stl(file("cube.stl"), "k", &read);
  EXPECT_TRUE(read.binary);
  EXPECT_EQ(m.vertices.size(), 8u);  // 36 corners welded
  EXPECT_EQ(m.triangles.size(), 12u);
  const MeshReport r = check_mesh(m, file("cube.stl"), "k", true);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.pieces, 1u);
  EXPECT_EQ(r.flipped, 0u);
  EXPECT_EQ(volume(m), 0.125);  // 0.5^3, exact: every product is of powers of two
  expect_consistent(m, true);
}

TEST_F(StlFile, AsciiKeepsTheDoublesBitwiseAndBinaryTheirFloats) {
  const TriangleMesh original = cube(1.0 / 3.0);  // no float: binary rounds it, ASCII must not
  write_stl(original, file("ascii.stl"), false);
  write_stl(original, file("binary.stl"), true);
  MeshReport ascii_report, binary_report;
  const TriangleMesh ascii = read_stl(file("ascii.stl"), "k", &ascii_report);
  const TriangleMesh binary = read_stl(file("binary.stl"), "k", &binary_report);
  EXPECT_FALSE(ascii_report.binary);
  EXPECT_TRUE(binary_report.binary);
  ASSERT_EQ(ascii.vertices.size(), 8u);
  ASSERT_EQ(binary.vertices.size(), 8u);
  ASSERT_EQ(ascii.triangles, binary.triangles);  // welded in first-use order: the same numbering
  ASSERT_EQ(ascii.triangles.size(), 12u);
  for (std::size_t t = 0; t < 12; ++t)
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        const double written = original.vertices[original.triangles[t][k]][a];
        EXPECT_EQ(std::bit_cast<std::uint64_t>(ascii.vertices[ascii.triangles[t][k]][a]),
                  std::bit_cast<std::uint64_t>(written));
        EXPECT_EQ(binary.vertices[binary.triangles[t][k]][a], double(float(written)));
      }
}

TEST_F(StlFile, BinaryHeaderStartingWithSolidIsStillBinary) {
  write_stl(cube(1.0), file("cad.stl"), true);
  {
    std::fstream f(file("cad.stl"), std::ios::in | std::ios::out | std::ios::binary);
    f.write("solid exported by some CAD", 26);
  }
  MeshReport read;
  const TriangleMesh m = read_stl(file("cad.stl"), "k", &read);
  EXPECT_TRUE(read.binary);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
}

TEST_F(StlFile, AsciiToleratesCaseSpacingAndSeveralSolids) {
  // Two solids (one triangle each, sharing an edge), odd case and spacing, a wrong normal.
  const std::string path = write_text("two.stl",
                                      "  SOLID first part\n facet normal 0 0 -1\n outer loop\n"
                                      "\tvertex 0 0 0\n vertex 1 0 0\n   vertex 1 1 0\nENDLOOP\n endfacet\n"
                                      "endsolid first part\r\nsolid\nFacet Normal 0 0 0 Outer Loop Vertex 0 0 0"
                                      " VERTEX 1 1 0 vertex +0 1e0 0 EndLoop EndFacet\nendsolid\n");
  TriangleMesh m = read_stl(path, "k");
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.vertices.size(), 4u);
  const MeshReport r = check_mesh(m, path, "k", false);
  EXPECT_EQ(r.flipped, 0u);  // both walk counter-clockwise about +z, whatever the normals say
  EXPECT_EQ(r.pieces, 1u);
  EXPECT_FALSE(r.closed);
}

TEST_F(StlFile, TrianglesTurnedOverAreTurnedBack) {
  TriangleMesh m = cube(1.0);
  for (std::size_t t : {2, 5, 9}) std::swap(m.triangles[t][1], m.triangles[t][2]);
  const MeshReport r = check_mesh(m, "mem", "k", true);
  EXPECT_EQ(r.flipped, 3u);
  EXPECT_TRUE(r.closed);
  expect_consistent(m, true);
  EXPECT_EQ(volume(m), 1.0);
  EXPECT_EQ(m.triangles, cube(1.0).triangles);  // each turned back by swapping its last corners
}

TEST_F(StlFile, FlipsCountTrianglesTurnedAgainstTheFile) {
  // Triangle 1 turned: the fill keeps it and turns the 11 others, then the piece faces inwards
  // and all 12 turn: only triangle 1 ends turned against the file.
  TriangleMesh m = cube(1.0);
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  EXPECT_EQ(check_mesh(m, "mem", "k", true).flipped, 1u);
  EXPECT_EQ(volume(m), 1.0);
}

TEST_F(StlFile, CubeInsideOutIsTurnedOutwards) {
  TriangleMesh m = cube(2.0);
  for (auto& t : m.triangles) std::swap(t[0], t[1]);
  EXPECT_EQ(volume(m), -8.0);
  const MeshReport r = check_mesh(m, "mem", "k", true);
  EXPECT_EQ(r.flipped, 12u);
  EXPECT_EQ(volume(m), 8.0);
  expect_consistent(m, true);
}

TEST_F(StlFile, OpenSquareIsAcceptedUnlessClosedIsRequired) {
  TriangleMesh m = square(4);
  std::swap(m.triangles[7][0], m.triangles[7][1]);
  write_stl(m, file("square.stl"), true);
  m = read_stl(file("square.stl"), "k");
  EXPECT_EQ(m.vertices.size(), 25u);
  EXPECT_EQ(m.triangles.size(), 32u);
  const MeshReport r = check_mesh(m, "mem", "k", false);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.pieces, 1u);
  EXPECT_EQ(r.flipped, 1u);  // an open piece keeps the winding of its triangle 1: +z
  expect_consistent(m, false);
  for (const auto& [a, b, c] : m.triangles)
    EXPECT_GT(cross(m.vertices[b] - m.vertices[a], m.vertices[c] - m.vertices[a]).z, 0.0);
  EXPECT_NE(refusal(file("square.stl"), true)
                .find("must be closed (closed = true) but the edge between vertices (0, 0, 0) and (0.25, 0, 0) of "
                      "triangle 1 belongs to no other triangle"),
            std::string::npos);
}

TEST_F(StlFile, PiecesAreCountedAndEachClosedOneFacesOutwards) {
  TriangleMesh m = square(2);
  const TriangleMesh box = cube(1.0);
  const auto offset = std::uint32_t(m.vertices.size());
  for (const Vec3& p : box.vertices) m.vertices.push_back(p + Vec3{0.0, 0.0, 5.0});
  for (const auto& t : box.triangles) m.triangles.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
  const MeshReport r = check_mesh(m, "mem", "k", false);
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.flipped, 12u);  // the cube was written inside out; the square is left as it is
}

TEST_F(StlFile, EmptyFilesAreRefused) {
  EXPECT_NE(refusal(write_text("empty.stl", "")).find("holds no triangles"), std::string::npos);
  EXPECT_NE(refusal(write_text("solid.stl", "solid nothing\nendsolid nothing\n")).find("holds no triangles"),
            std::string::npos);
  std::string header(84, '\0');  // binary, with a count of 0
  EXPECT_NE(refusal(write_text("zero.stl", header)).find("holds no triangles"), std::string::npos);
}

TEST_F(StlFile, TruncatedBinaryIsRefusedWithItsSizes) {
  write_stl(cube(1.0), file("cut.stl"), true);
  std::filesystem::resize_file(file("cut.stl"), 684 - 10);
  const std::string reason = refusal(file("cut.stl"));
  EXPECT_NE(reason.find("truncated"), std::string::npos) << reason;
  EXPECT_NE(reason.find("12 triangles has 684 bytes, this one 674"), std::string::npos) << reason;
}

TEST_F(StlFile, NonFiniteCoordinatesNameTheirTriangle) {
  write_stl(cube(1.0), file("nan.stl"), true);
  {
    std::fstream f(file("nan.stl"), std::ios::in | std::ios::out | std::ios::binary);
    const float nan = std::nanf("");
    f.seekp(84 + 50 * 4 + 12 + 4 * 4);  // triangle 5, its second corner's y
    f.write(reinterpret_cast<const char*>(&nan), 4);
  }
  EXPECT_EQ(refusal(file("nan.stl")), "triangle 5 has a non-finite coordinate");
  write_stl(cube(1.0), file("inf.stl"), false);
  std::ifstream in(file("inf.stl"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t last_vertex = text.rfind("vertex");
  text.replace(last_vertex, 8, "vertex inf");  // the first coordinate of triangle 12's last corner
  EXPECT_EQ(refusal(write_text("inf2.stl", text)), "triangle 12 has a non-finite coordinate");
}

TEST_F(StlFile, MalformedAsciiNamesItsLine) {
  const std::string path = write_text("bad.stl",
                                      "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n"
                                      "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
  EXPECT_EQ(refusal(path), "line 6: expected 'vertex x y z'");  // "vertex 1 0" reads the next line's word
  EXPECT_EQ(refusal(write_text("cut.stl", "solid s\nfacet normal 0 0 1\nouter loop\n")),
            "line 3: expected 'vertex x y z'");
}

TEST_F(StlFile, ZeroAreaTrianglesAreRefused) {
  TriangleMesh m = cube(1.0);
  m.vertices.push_back({0.5, 0.0, 0.0});  // on the edge from vertex 0 to vertex 1
  m.triangles.push_back({0, 1, 8});
  write_stl(m, file("flat.stl"), false);
  EXPECT_EQ(refusal(file("flat.stl")), "triangle 13 has zero area");
  m.triangles[12] = {3, 5, 3};  // two corners the same vertex
  EXPECT_EQ(refusal(m), "triangle 13 has zero area");
  // Against the mesh's size: the same cube a million times smaller keeps its 1e-12 m^2 faces.
  m = cube(1e-6);
  EXPECT_EQ(check_mesh(m, "mem", "k", true).pieces, 1u);
}

TEST_F(StlFile, AnEdgeOfThreeTrianglesIsRefused) {
  TriangleMesh m = cube(1.0);
  m.vertices.push_back({0.5, -1.0, -1.0});
  m.triangles.push_back({0, 1, 8});  // a fin on the edge from (0,0,0) to (1,0,0)
  write_stl(m, file("fin.stl"), true);
  const std::string reason = refusal(file("fin.stl"));
  EXPECT_NE(reason.find("the edge between vertices (0, 0, 0) and (1, 0, 0) belongs to more than two triangles"),
            std::string::npos)
      << reason;
  EXPECT_NE(reason.find(" and 13)"), std::string::npos) << reason;
}

TEST_F(StlFile, MoebiusStripIsRefused) {
  // 12 segments about the z axis; the strip's cross-section turns half a turn on the way round, so
  // that the end joins the start upside down.
  constexpr int n = 12;
  TriangleMesh m;
  for (int k = 0; k < n; ++k)
    for (double s : {-1.0, 1.0}) {
      const double phi = 2.0 * M_PI * k / n, r = 3.0 + s * std::cos(phi / 2.0);
      m.vertices.push_back({r * std::cos(phi), r * std::sin(phi), s * std::sin(phi / 2.0)});
    }
  const auto at = [&](int k, int s) { return std::uint32_t(k < n ? 2 * k + s : 2 * 0 + (1 - s)); };
  for (int k = 0; k < n; ++k) {
    m.triangles.push_back({at(k, 0), at(k + 1, 0), at(k + 1, 1)});
    m.triangles.push_back({at(k, 0), at(k + 1, 1), at(k, 1)});
  }
  write_stl(m, file("moebius.stl"), false);
  const std::string reason = refusal(file("moebius.stl"));
  EXPECT_NE(reason.find("one-sided (as a Moebius strip)"), std::string::npos) << reason;
  EXPECT_EQ(reason.rfind("triangle ", 0), 0u) << reason;
}

TEST_F(StlFile, HundredThousandTrianglesReadAndCheck) {
  // 224^2 cells: 100352 triangles. A quadratic step would take minutes here.
  for (bool binary : {true, false}) {
    write_stl(square(224), file("big.stl"), binary);
    TriangleMesh m = read_stl(file("big.stl"), "k");
    EXPECT_EQ(m.triangles.size(), 100352u);
    EXPECT_EQ(m.vertices.size(), 225u * 225u);
    EXPECT_EQ(check_mesh(m, "mem", "k", false).pieces, 1u);
  }
}

}  // namespace
