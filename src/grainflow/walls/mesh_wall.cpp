#include "grainflow/walls/mesh_wall.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>

#include "grainflow/config/toml_reader.hpp"
#include "grainflow/core/error.hpp"

namespace grainflow::walls {
namespace {

// A surface per file and placement: the loader checks the file and the engine, the snapshots and
// the checks build their shapes from the same keys; the file is read once.
std::shared_ptr<const MeshSurface> load(const GeometryKeys& k) {
  static std::mutex guard;
  static std::map<std::string, std::shared_ptr<const MeshSurface>> loaded;
  const std::string& path = k.text("file");
  std::ostringstream key;
  key.precision(17);
  const Vec3 axis = k.vector("rotate_axis"), shift = k.vector("translate");
  key << path << ' ' << k.number("scale") << ' ' << axis.x << ' ' << axis.y << ' ' << axis.z << ' '
      << k.number("rotate_degrees") << ' ' << shift.x << ' ' << shift.y << ' ' << shift.z << ' ' << k.boolean("closed");
  const std::lock_guard lock(guard);
  if (auto it = loaded.find(key.str()); it != loaded.end()) return it->second;
  MeshReport read;
  TriangleMesh mesh = read_stl(path, "file", &read);
  MeshReport report = check_mesh(mesh, path, "file", k.boolean("closed"));
  report.binary = read.binary;
  const Rotation turn = Rotation::about(axis * (M_PI / 180.0 * k.number("rotate_degrees") / norm(axis)), 1.0);
  for (Vec3& v : mesh.vertices) v = turn(k.number("scale") * v) + shift;
  std::shared_ptr<const MeshSurface> surface;
  try {
    surface = std::make_shared<const MeshSurface>(mesh, report);
  } catch (const std::invalid_argument& e) {  // a sliver that the scaling or turning flattened
    throw InputError(path, "file", e.what());
  }
  loaded.emplace(key.str(), surface);
  return surface;
}

}  // namespace

void MeshWall::read(TomlReader& r, GeometryKeys& out) {
  if (!r.has("file")) r.fail("file", "is required: the STL file (binary or ASCII), relative to the case file");
  std::filesystem::path file = r.string("file", "");
  if (file.is_relative()) file = std::filesystem::path(r.file()).parent_path() / file;
  if (!std::filesystem::is_regular_file(file)) r.fail("file", "'" + file.string() + "' is not a readable file");
  out.set_text("file", std::filesystem::absolute(file).lexically_normal().string());  // a written case finds it from anywhere
  const double scale = r.number("scale", 1.0);
  if (!(scale > 0.0) || !std::isfinite(scale)) r.fail("scale", "must be positive (file units to the case's units)");
  out.set_number("scale", scale);
  out.set_vector("translate", r.vec3("translate", {}));
  const Vec3 axis = r.vec3("rotate_axis", {0.0, 0.0, 1.0});
  if (!(norm(axis) > 0.0)) r.fail("rotate_axis", "must not be the zero vector");
  out.set_vector("rotate_axis", axis * (1.0 / norm(axis)));
  out.set_number("rotate_degrees", r.number("rotate_degrees", 0.0));
  out.set_boolean("closed", r.boolean("closed", false));
  load(out);  // the file's own errors now, before anything runs
}

MeshWall MeshWall::from_keys(const GeometryKeys& keys) {
  MeshWall w;
  w.surface = load(keys);
  return w;
}

SurfaceMesh MeshWall::mesh(const Vec3&, const Vec3&) const {
  SurfaceMesh m;
  m.points.reserve(surface->vertices().size());
  for (const Vec3& v : surface->vertices()) m.points.push_back(pose.point(v));
  m.triangles.reserve(surface->size());
  for (const MeshFacet& f : surface->facets())
    m.triangles.push_back({static_cast<int>(f.vertex[0]), static_cast<int>(f.vertex[1]), static_cast<int>(f.vertex[2])});
  return m;
}

}  // namespace grainflow::walls
