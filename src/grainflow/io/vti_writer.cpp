#include "grainflow/io/vti_writer.hpp"

#include <cstdio>
#include <ostream>
#include <stdexcept>

#include "grainflow/io/atomic_file.hpp"

namespace grainflow::io {
namespace {

std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

const char* attribute_for(int components) {
  return components == 1 ? "Scalars" : components == 3 ? "Vectors" : "Tensors";
}

}  // namespace

void write_vti(const std::string& path, const ImageGrid& grid, const std::vector<CellArray>& cell_data,
               const std::vector<std::pair<std::string, double>>& field_data) {
  const std::size_t cells = static_cast<std::size_t>(grid.cells[0]) * grid.cells[1] * grid.cells[2];
  for (const CellArray& a : cell_data)
    if (a.values.size() != cells * static_cast<std::size_t>(a.components))
      throw std::invalid_argument("cell array '" + a.name + "' does not match the grid");
  write_atomically(path, [&](std::ostream& out) {
    const std::string extent = "0 " + std::to_string(grid.cells[0]) + " 0 " + std::to_string(grid.cells[1]) + " 0 " +
                               std::to_string(grid.cells[2]);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        << "  <ImageData WholeExtent=\"" << extent << "\" Origin=\"" << exact(grid.origin[0]) << ' '
        << exact(grid.origin[1]) << ' ' << exact(grid.origin[2]) << "\" Spacing=\"" << exact(grid.spacing[0]) << ' '
        << exact(grid.spacing[1]) << ' ' << exact(grid.spacing[2]) << "\">\n";
    if (!field_data.empty()) {
      out << "    <FieldData>\n";
      for (const auto& [name, value] : field_data)
        out << "      <DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfTuples=\"1\" format=\"ascii\">"
            << exact(value) << "</DataArray>\n";
      out << "    </FieldData>\n";
    }
    out << "    <Piece Extent=\"" << extent << "\">\n      <PointData>\n      </PointData>\n      <CellData";
    // The first array of each kind is the one ParaView colours by.
    for (int components : {1, 3, 9})
      for (const CellArray& a : cell_data)
        if (a.components == components) {
          out << ' ' << attribute_for(components) << "=\"" << a.name << '"';
          break;
        }
    out << ">\n";
    for (const CellArray& a : cell_data) {
      out << "        <DataArray type=\"Float64\" Name=\"" << a.name << "\" NumberOfComponents=\"" << a.components
          << "\" format=\"ascii\">\n";
      for (std::size_t k = 0; k < cells; ++k) {
        out << "         ";
        for (int c = 0; c < a.components; ++c) out << ' ' << exact(a.values[k * a.components + c]);
        out << '\n';
      }
      out << "        </DataArray>\n";
    }
    out << "      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
  });
}

}  // namespace grainflow::io
