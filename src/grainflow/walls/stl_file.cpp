#include "grainflow/walls/stl_file.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>
#include <unordered_map>

#include "grainflow/core/error.hpp"

namespace grainflow::walls {

namespace {

// Binary STL is little-endian; the reader copies its floats and counts as they lie.
static_assert(std::endian::native == std::endian::little, "the binary STL reader assumes a little-endian machine");

constexpr std::size_t kHeaderBytes = 84;    // 80-byte header and the uint32 triangle count
constexpr std::size_t kTriangleBytes = 50;  // normal and 3 corners (12 float32) and a uint16
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

std::string triangle_name(std::size_t t) { return "triangle " + std::to_string(t + 1); }

std::string point_text(const Vec3& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
  return buffer;
}

// splitmix64's finaliser: the bits of coordinates and vertex numbers are far from random, and
// libstdc++'s std::hash of an integer is the integer itself.
std::uint64_t mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

using PointBits = std::array<std::uint64_t, 3>;
struct PointHash {
  std::size_t operator()(const PointBits& b) const { return mix(b[0] ^ mix(b[1] ^ mix(b[2]))); }
};
struct EdgeHash {
  std::size_t operator()(std::uint64_t e) const { return mix(e); }
};

// Collects triangles, welding corners whose coordinates are the same bits into one vertex.
class Welder {
 public:
  Welder(const std::string& path, const std::string& key) : path_(path), key_(key) {}

  void add(const std::array<Vec3, 3>& corners) {
    std::array<std::uint32_t, 3> t;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = corners[k];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw InputError(path_, key_, triangle_name(mesh.triangles.size()) + " has a non-finite coordinate");
      t[k] = vertex(p);
    }
    mesh.triangles.push_back(t);
  }

  TriangleMesh mesh;

 private:
  std::uint32_t vertex(const Vec3& p) {
    // -0 and +0 are one position: both key as +0.
    const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v); };
    const auto [it, added] = index_.try_emplace({bits(p.x), bits(p.y), bits(p.z)}, mesh.vertices.size());
    if (added) mesh.vertices.push_back(p);
    return it->second;
  }

  const std::string& path_;
  const std::string& key_;
  std::unordered_map<PointBits, std::uint32_t, PointHash> index_;
};

void read_binary(const std::string& data, Welder& welder) {
  std::uint32_t count;
  std::memcpy(&count, data.data() + 80, 4);
  for (std::size_t t = 0; t < count; ++t) {
    float f[12];  // the normal (ignored: the winding defines the front) and the 3 corners
    std::memcpy(f, data.data() + kHeaderBytes + kTriangleBytes * t, sizeof f);
    welder.add({Vec3{f[3], f[4], f[5]}, Vec3{f[6], f[7], f[8]}, Vec3{f[9], f[10], f[11]}});
  }
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// ASCII STL read word by word, each word's line counted, so that any spacing and line breaking reads.
class AsciiParser {
 public:
  AsciiParser(const std::string& data, const std::string& path, const std::string& key, Welder& welder)
      : data_(data), path_(path), key_(key), welder_(welder) {}

  // One or more solids, each of facets.
  void parse() {
    while (!peek().empty()) {
      expect("solid", "expected 'solid'");
      skip_rest_of_line();  // the solid's name
      for (std::string_view word = peek(); !word.empty() && !equals_ignoring_case(word, "endsolid"); word = peek())
        facet();
      expect("endsolid", "expected 'endsolid'");
      skip_rest_of_line();
    }
  }

 private:
  void facet() {
    expect("facet", "expected 'facet normal nx ny nz' or 'endsolid'");
    // The normal written in the file is ignored: the corners' winding defines the front (exporters
    // often write zero or stale normals).
    if (const std::string_view word = peek(); equals_ignoring_case(word, "normal")) {
      take(word);
      point("expected 'facet normal nx ny nz'");
    }
    expect("outer", "expected 'outer loop'");
    expect("loop", "expected 'outer loop'");
    std::array<Vec3, 3> corners;
    for (Vec3& c : corners) {
      expect("vertex", "expected 'vertex x y z'");
      c = point("expected 'vertex x y z'");
    }
    expect("endloop", "expected 'endloop'");
    expect("endfacet", "expected 'endfacet'");
    welder_.add(corners);
  }

  // The next word (empty at the end of the file), left unread.
  std::string_view peek() {
    for (; at_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[at_])); ++at_)
      if (data_[at_] == '\n') ++line_;
    std::size_t end = at_;
    while (end < data_.size() && !std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
    return std::string_view(data_).substr(at_, end - at_);
  }

  void take(std::string_view word) { at_ += word.size(); }

  // The line of the word that is not what was expected (the last line at the end of the file).
  [[noreturn]] void fail(const char* what) {
    if (peek().empty())
      line_ = 1 + std::count(data_.begin(), data_.begin() + data_.find_last_not_of(" \t\r\n\f\v"), '\n');
    throw InputError(path_, key_, "line " + std::to_string(line_) + ": " + what);
  }

  void expect(std::string_view word, const char* what) {
    const std::string_view next = peek();
    if (!equals_ignoring_case(next, word)) fail(what);
    take(next);
  }

  Vec3 point(const char* what) {
    Vec3 p;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string_view word = peek();
      const std::string_view text = word.starts_with('+') ? word.substr(1) : word;  // from_chars takes no '+'
      // from_chars: independent of the locale, and reads "nan" and "inf" (refused later by triangle).
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), p[axis]);
      if (error != std::errc() || end != text.data() + text.size()) fail(what);
      take(word);
    }
    return p;
  }

  void skip_rest_of_line() { at_ = std::min(data_.find('\n', at_), data_.size()); }

  const std::string& data_;
  const std::string& path_;
  const std::string& key_;
  Welder& welder_;
  std::size_t at_ = 0, line_ = 1;
};

// Binary when the size matches the count at offset 80, even if the header starts with "solid" (as
// some CAD exporters write); otherwise ASCII if it starts with "solid".
bool is_binary(const std::string& data) {
  if (data.size() >= kHeaderBytes) {
    std::uint32_t count;
    std::memcpy(&count, data.data() + 80, 4);
    if (data.size() == kHeaderBytes + kTriangleBytes * std::size_t{count}) return true;
  }
  const std::size_t first = data.find_first_not_of(" \t\r\n\f\v");
  return first == std::string::npos || !equals_ignoring_case(std::string_view(data).substr(first, 5), "solid");
}

}  // namespace

TriangleMesh read_stl(const std::string& path, const std::string& key, MeshReport* report) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, key, "cannot be read");
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, key, "cannot be read");
  if (data.empty()) throw InputError(path, key, "holds no triangles (the file is empty)");

  const bool binary = is_binary(data);
  Welder welder(path, key);
  if (binary) {
    if (data.size() < kHeaderBytes)
      throw InputError(
          path, key, "is truncated: a binary STL file has at least 84 bytes, this one " + std::to_string(data.size()));
    std::uint32_t count;
    std::memcpy(&count, data.data() + 80, 4);
    const std::size_t expected = kHeaderBytes + kTriangleBytes * std::size_t{count};
    if (data.size() != expected)
      throw InputError(path, key,
                       "is truncated (or not STL): a binary STL file of " + std::to_string(count) + " triangles has " +
                           std::to_string(expected) + " bytes, this one " + std::to_string(data.size()));
    read_binary(data, welder);
  } else {
    AsciiParser(data, path, key, welder).parse();
  }
  if (welder.mesh.triangles.empty()) throw InputError(path, key, "holds no triangles");
  if (report) report->binary = binary;
  return std::move(welder.mesh);
}

MeshReport check_mesh(TriangleMesh& mesh, const std::string& path, const std::string& key, bool must_be_closed) {
  const auto fail = [&](const std::string& reason) { throw InputError(path, key, reason); };
  const auto& v = mesh.vertices;
  auto& tris = mesh.triangles;
  const std::size_t n = tris.size();
  if (n == 0) fail("holds no triangles");

  // Degenerate triangles, against the size of the whole mesh so that the test is free of units.
  Vec3 lo = v.empty() ? Vec3{} : v[0], hi = lo;
  for (const Vec3& p : v)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  const double min_area = 1e-12 * norm2(hi - lo);
  for (std::size_t t = 0; t < n; ++t) {
    const auto& [a, b, c] = tris[t];
    if (std::max({a, b, c}) >= v.size())
      fail(triangle_name(t) + " names a vertex beyond the mesh's " + std::to_string(v.size()));
    if (a == b || b == c || c == a || !(0.5 * norm(cross(v[b] - v[a], v[c] - v[a])) > min_area))
      fail(triangle_name(t) + " has zero area");
  }

  // The triangles on each edge (a sorted pair of vertices), and each triangle's neighbour across
  // its edge k (from corner k to corner k + 1).
  const auto edge_key = [&](std::size_t t, int k) {
    const std::uint64_t a = tris[t][k], b = tris[t][(k + 1) % 3];
    return std::min(a, b) << 32 | std::max(a, b);
  };
  std::unordered_map<std::uint64_t, std::array<std::uint32_t, 2>, EdgeHash> edges;
  edges.reserve(2 * n);
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = edges.try_emplace(edge_key(t, k), std::array{std::uint32_t(t), kNone});
      if (added) continue;
      if (it->second[1] != kNone)
        fail("the edge between vertices " + point_text(v[it->first >> 32]) + " and " +
             point_text(v[it->first & 0xffffffffu]) + " belongs to more than two triangles (triangles " +
             std::to_string(it->second[0] + 1) + ", " + std::to_string(it->second[1] + 1) + " and " +
             std::to_string(t + 1) + ")");
      it->second[1] = std::uint32_t(t);
    }
  std::vector<std::array<std::uint32_t, 3>> neighbour(n);
  bool closed = true;
  for (std::size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto& on_edge = edges.at(edge_key(t, k));
      neighbour[t][k] = on_edge[0] == t ? on_edge[1] : on_edge[0];
      if (neighbour[t][k] != kNone) continue;
      if (must_be_closed)
        fail("the mesh must be closed (closed = true) but the edge between vertices " + point_text(v[tris[t][k]]) +
             " and " + point_text(v[tris[t][(k + 1) % 3]]) + " of " + triangle_name(t) +
             " belongs to no other triangle");
      closed = false;
    }

  // Flood fill over each piece from its lowest-numbered triangle, which keeps its winding: a
  // neighbour walking the shared edge in the same direction as its turned-over state says is turned.
  const auto walks = [&](std::size_t t, std::uint32_t a, std::uint32_t b) {
    for (int k = 0; k < 3; ++k)
      if (tris[t][k] == a && tris[t][(k + 1) % 3] == b) return true;
    return false;
  };
  enum : std::uint8_t { kUnseen, kKeep, kFlip };
  std::vector<std::uint8_t> state(n, kUnseen);
  std::vector<std::uint32_t> piece;  // the triangles of the piece being filled
  MeshReport report;
  report.closed = closed;
  for (std::size_t first = 0; first < n; ++first) {
    if (state[first] != kUnseen) continue;
    ++report.pieces;
    piece.assign(1, std::uint32_t(first));
    state[first] = kKeep;
    bool piece_closed = true;
    for (std::size_t next = 0; next < piece.size(); ++next) {
      const std::uint32_t t = piece[next];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = neighbour[t][k];
        if (u == kNone) {
          piece_closed = false;
          continue;
        }
        const bool same_direction = walks(u, tris[t][k], tris[t][(k + 1) % 3]);
        const std::uint8_t wanted = (state[t] == kFlip) != same_direction ? kFlip : kKeep;
        if (state[u] == kUnseen) {
          state[u] = wanted;
          piece.push_back(u);
        } else if (state[u] != wanted) {
          fail(triangle_name(u) +
               " cannot be given a front that agrees with all its neighbours: its piece of "
               "the mesh is one-sided (as a Moebius strip)");
        }
      }
    }
    // A closed piece faces outwards: its enclosed volume, with the corrected winding, positive.
    // (Taken about one of its corners, which keeps the products small for a mesh far from 0.)
    if (!piece_closed) continue;
    const Vec3 o = v[tris[first][0]];
    double volume6 = 0.0;
    for (std::uint32_t t : piece) {
      const auto& [a, b, c] = tris[t];
      const double signed6 = dot(v[a] - o, cross(v[b] - o, v[c] - o));
      volume6 += state[t] == kFlip ? -signed6 : signed6;
    }
    if (volume6 < 0.0)
      for (std::uint32_t t : piece) state[t] = state[t] == kFlip ? kKeep : kFlip;
  }
  // Turn over: swapping two corners reverses the walk around the triangle.
  for (std::size_t t = 0; t < n; ++t)
    if (state[t] == kFlip) {
      std::swap(tris[t][1], tris[t][2]);
      ++report.flipped;
    }
  return report;
}

void write_stl(const TriangleMesh& mesh, const std::string& path, bool binary) {
  std::string out;
  const auto normal = [&](const std::array<std::uint32_t, 3>& t) {
    const Vec3 n = cross(mesh.vertices[t[1]] - mesh.vertices[t[0]], mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double length = norm(n);
    return length > 0.0 ? n * (1.0 / length) : n;
  };
  if (binary) {
    out = "grainflow binary STL";  // a header that does not start with "solid"
    out.resize(80, '\0');
    const auto put = [&](const auto& value) { out.append(reinterpret_cast<const char*>(&value), sizeof value); };
    put(std::uint32_t(mesh.triangles.size()));
    for (const auto& t : mesh.triangles) {
      const Vec3 n = normal(t);
      for (const Vec3& p : {n, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]})
        for (int a = 0; a < 3; ++a) put(float(p[a]));
      put(std::uint16_t{0});
    }
  } else {
    // Shortest text that reads back as the same double (std::to_chars), so ASCII round-trips.
    const auto put = [&](const char* word, const Vec3& p) {
      out += word;
      for (int a = 0; a < 3; ++a) {
        char buffer[32];
        out += ' ';
        out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, p[a]).ptr);
      }
      out += '\n';
    };
    out = "solid grainflow\n";
    for (const auto& t : mesh.triangles) {
      put("  facet normal", normal(t));
      out += "    outer loop\n";
      for (std::uint32_t corner : t) put("      vertex", mesh.vertices[corner]);
      out += "    endloop\n  endfacet\n";
    }
    out += "endsolid grainflow\n";
  }
  std::ofstream file(path, std::ios::binary);
  file.write(out.data(), std::streamsize(out.size()));
  if (!file) throw RunError("cannot write the STL file " + path);
}

}  // namespace grainflow::walls
