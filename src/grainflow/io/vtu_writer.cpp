#include "grainflow/io/vtu_writer.hpp"

#include <cstdio>
#include <filesystem>

#include "grainflow/io/atomic_file.hpp"

namespace grainflow::io {
namespace {

template <class Get>
void vector_array(std::ostream& out, const char* name, std::size_t n, Get get) {
  out << "        <DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 v = get(i);
    out << v.x << ' ' << v.y << ' ' << v.z << '\n';
  }
  out << "        </DataArray>\n";
}

}  // namespace

void write_vtu(const std::string& path, const ParticleStore& p) {
  write_atomically(path, [&](std::ostream& out) {
    const std::size_t n = p.size();
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
        << "      <PointData Scalars=\"diameter\" Vectors=\"velocity\">\n";
    out << "        <DataArray type=\"Float64\" Name=\"diameter\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << 2.0 * p.radius[i] << '\n';
    out << "        </DataArray>\n";
    out << "        <DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << p.radius[i] << '\n';
    out << "        </DataArray>\n";
    vector_array(out, "velocity", n, [&](std::size_t i) { return p.velocity[i]; });
    vector_array(out, "angular_velocity", n, [&](std::size_t i) { return p.angular_velocity[i]; });
    out << "        <DataArray type=\"Int32\" Name=\"species\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << p.species[i] << '\n';
    out << "        </DataArray>\n";
    out << "        <DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << p.id[i] << '\n';
    out << "        </DataArray>\n";
    out << "      </PointData>\n      <Points>\n";
    vector_array(out, "position", n, [&](std::size_t i) { return p.position[i]; });
    out << "      </Points>\n      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << i << '\n';
    out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << i + 1 << '\n';
    out << "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out << "1\n";  // VTK_VERTEX
    out << "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

void PvdSeries::add(const ParticleStore& particles, double time) {
  std::filesystem::create_directories(directory_);
  char name[32];
  std::snprintf(name, sizeof name, "particles_%06zu.vtu", entries_.size());
  write_vtu(directory_ + "/" + name, particles);
  entries_.emplace_back(time, name);
  write_atomically(directory_ + "/particles.pvd", [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& [t, file] : entries_)
      out << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace grainflow::io
