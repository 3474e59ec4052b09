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

// The particles a file shows: all but the ghosts (an MPI rank's copies of its neighbours').
std::vector<std::size_t> shown_particles(const ParticleStore& p) {
  std::vector<std::size_t> shown;
  shown.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.owned(i)) shown.push_back(i);
  return shown;
}

// The point arrays of a snapshot, as a parallel index (.pvtu) declares them.
constexpr const char* kPointArrays =
    "        <PDataArray type=\"Float64\" Name=\"diameter\"/>\n"
    "        <PDataArray type=\"Float64\" Name=\"radius\"/>\n"
    "        <PDataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\"/>\n"
    "        <PDataArray type=\"Float64\" Name=\"angular_velocity\" NumberOfComponents=\"3\"/>\n"
    "        <PDataArray type=\"Int32\" Name=\"species\"/>\n"
    "        <PDataArray type=\"Int64\" Name=\"id\"/>\n";

}  // namespace

void write_vtu(const std::string& path, const ParticleStore& p) {
  const std::vector<std::size_t> shown = shown_particles(p);
  write_atomically(path, [&](std::ostream& out) {
    const std::size_t n = shown.size();
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
        << "      <PointData Scalars=\"diameter\" Vectors=\"velocity\">\n";
    out << "        <DataArray type=\"Float64\" Name=\"diameter\" format=\"ascii\">\n";
    for (std::size_t i : shown) out << 2.0 * p.radius[i] << '\n';
    out << "        </DataArray>\n";
    out << "        <DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n";
    for (std::size_t i : shown) out << p.radius[i] << '\n';
    out << "        </DataArray>\n";
    vector_array(out, "velocity", n, [&](std::size_t k) { return p.velocity[shown[k]]; });
    vector_array(out, "angular_velocity", n, [&](std::size_t k) { return p.angular_velocity[shown[k]]; });
    out << "        <DataArray type=\"Int32\" Name=\"species\" format=\"ascii\">\n";
    for (std::size_t i : shown) out << p.species[i] << '\n';
    out << "        </DataArray>\n";
    out << "        <DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">\n";
    for (std::size_t i : shown) out << p.id[i] << '\n';
    out << "        </DataArray>\n";
    out << "      </PointData>\n      <Points>\n";
    vector_array(out, "position", n, [&](std::size_t k) { return p.position[shown[k]]; });
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

void write_pvtu(const std::string& path, const std::vector<std::string>& pieces) {
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
        << "      <PPointData Scalars=\"diameter\" Vectors=\"velocity\">\n"
        << kPointArrays << "      </PPointData>\n"
        << "      <PPoints>\n        <PDataArray type=\"Float64\" Name=\"position\" NumberOfComponents=\"3\"/>\n"
        << "      </PPoints>\n";
    for (const auto& piece : pieces) out << "    <Piece Source=\"" << piece << "\"/>\n";
    out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  });
}

void PvdSeries::add(const ParticleStore& particles, double time) {
  std::filesystem::create_directories(directory_);
  char name[48];
  std::snprintf(name, sizeof name, "particles_%06zu.vtu", entries_.size());
  write_vtu(directory_ + "/" + name, particles);
  entries_.emplace_back(time, name);
  write_index();
}

void PvdSeries::add_piece(const ParticleStore& particles, double time, int rank, int ranks) {
  std::filesystem::create_directories(directory_);
  char piece[64];
  std::snprintf(piece, sizeof piece, "particles_%06zu_rank%d.vtu", entries_.size(), rank);
  write_vtu(directory_ + "/" + piece, particles);
  char index[48];
  std::snprintf(index, sizeof index, "particles_%06zu.pvtu", entries_.size());
  entries_.emplace_back(time, index);
  if (rank != 0) return;
  std::vector<std::string> pieces;
  for (int r = 0; r < ranks; ++r) {
    std::snprintf(piece, sizeof piece, "particles_%06zu_rank%d.vtu", entries_.size() - 1, r);
    pieces.emplace_back(piece);
  }
  write_pvtu(directory_ + "/" + index, pieces);
  write_index();
}

std::string PvdSeries::part_file(const Part& part, std::size_t index) {
  if (!part.per_snapshot) return part.stem + ".vtp";
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_%06zu.vtp", index);
  return part.stem + suffix;
}

void PvdSeries::write_index() const {
  write_atomically(directory_ + "/particles.pvd", [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (std::size_t k = 0; k < entries_.size(); ++k) {
      const auto& [t, file] = entries_[k];
      out << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"0\" file=\"" << file << "\"/>\n";
      // Parts 1, 2, ...: ParaView shows them with the particles at the same time.
      for (std::size_t p = 0; p < parts_.size(); ++p)
        out << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"" << p + 1 << "\" file=\""
            << part_file(parts_[p], k) << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace grainflow::io
