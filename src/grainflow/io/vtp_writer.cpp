#include "grainflow/io/vtp_writer.hpp"

#include <iomanip>
#include <limits>

#include "grainflow/io/atomic_file.hpp"

namespace grainflow::io {

void write_vtp(const std::string& path, const std::vector<Vec3>& points,
               const std::vector<std::array<int, 3>>& triangles) {
  write_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(std::numeric_limits<double>::max_digits10);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <PolyData>\n"
        << "    <Piece NumberOfPoints=\"" << points.size() << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\""
        << " NumberOfStrips=\"0\" NumberOfPolys=\"" << triangles.size() << "\">\n"
        << "      <Points>\n"
        << "        <DataArray type=\"Float64\" Name=\"position\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& p : points) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
    out << "        </DataArray>\n      </Points>\n      <Polys>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& t : triangles) out << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < triangles.size(); ++k) out << 3 * (k + 1) << '\n';
    out << "        </DataArray>\n      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  });
}

}  // namespace grainflow::io
