// stresses.csv and walls.csv, the one format both engines write (OUTPUTS.md): the strips' stress
// tensor in parts with block-averaged errors, and each wall's row of it.
#pragma once

#include <string>
#include <vector>

#include "grainflow/core/face_wall.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/observe/collision_stress.hpp"
#include "grainflow/observe/wall_stress.hpp"

namespace grainflow::observe {

struct StressFileLayout {
  int dimension = 3;
  bool between_walls = false;                // a y_over_H column
  const char* contact_part = "collisional";  // the name of the non-kinetic part's columns
  bool collisions = true;                    // the collision and dissipation rates mean something (else nan)
};

void write_stress_file(const std::string& path, const std::vector<StripStress>& strips, const StressFileLayout& layout);

// `areas[w]`: wall w's area (2D: length) now, m^(D-1); `time` places the walls.
void write_wall_file(const std::string& path, const std::vector<WallLoad>& loads, const FaceWalls& walls,
                     const std::vector<double>& areas, double time, int dimension);

// P_y. at the top of the strips, where the weight integral starts: the top wall's row between two
// walls, zero at a free surface.
Vec3 top_wall_row(const std::vector<WallLoad>& loads, const FaceWalls& walls, bool between_walls);

// summary.json's stress_samples, stress_averaging_time and each wall's wall_*_<face> keys.
void add_stress_summary(io::JsonObject& summary, const StressProfile& stress, const std::vector<WallLoad>& loads,
                        const FaceWalls& walls);

// The area of the wall on `axis` in a box of this dimension: the product of the other lengths.
template <class Box>
double wall_area(const Box& box, int axis, int dimension) {
  double area = 1.0;
  for (int a = 0; a < dimension; ++a)
    if (a != axis) area *= box.length(a);
  return area;
}

}  // namespace grainflow::observe
