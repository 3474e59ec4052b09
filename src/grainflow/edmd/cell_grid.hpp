// The event-driven engine's cell grid: cells at least a diameter wide (on the neighbour-list path,
// a diameter and two shells), each holding its particles in a doubly linked list. The links'
// `next` lives in the engine's flight records, beside the position a cell search reads next (one
// cache line per partner), so the list operations take that node array; the heads and `prev`,
// read only when a particle changes cells, live here.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "grainflow/core/cell_counts.hpp"
#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"
#include "grainflow/edmd/free_flight.hpp"
#include "grainflow/edmd/lees_edwards.hpp"

namespace grainflow::edmd {

template <int Dim>
class CellGrid {
 public:
  template <class Archive>
  void serialize(Archive& ar) {
    ar(cells_, cell_size_, head_, prev_, cell_);
  }

  // An empty grid over `box` for `particles` particles: cells at least `min_width` wide along the
  // first Dim axes, at most 2^11 per axis and `max_cells` in all (core/cell_counts.hpp).
  void reset(const PeriodicBox& box, double min_width, double max_cells, std::size_t particles) {
    const std::array<double, 3> lengths{box.length(0), box.length(1), box.length(2)};
    cells_ = cell_counts(lengths, Dim, min_width, 1 << 11, max_cells);
    for (int a = 0; a < 3; ++a) cell_size_[a] = box.length(a) / cells_[a];
    head_.assign(static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2], -1);
    prev_.assign(particles, -1);
    cell_.assign(particles, 0);
  }

  int count(int axis) const { return cells_[axis]; }         // cells along an axis
  double width(int axis) const { return cell_size_[axis]; }  // m
  std::size_t size() const { return head_.size(); }          // cells in all
  int head(int cell) const { return head_[cell]; }           // first particle in a cell, -1 when empty
  int cell(int i) const { return cell_[i]; }                 // the cell particle i is filed in

  int index(int cx, int cy, int cz) const { return cx + cells_[0] * (cy + cells_[1] * cz); }
  std::array<int, 3> coordinates(int cell) const {
    return {cell % cells_[0], (cell / cells_[0]) % cells_[1], cell / (cells_[0] * cells_[1])};
  }
  // The cell holding x (the edge cells also hold what lies just outside by round-off).
  int cell_of(const PeriodicBox& box, const Vec3& x) const {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < Dim; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor((x[a] - box.lo[a]) / cell_size_[a])), 0, cells_[a] - 1);
    return index(c[0], c[1], c[2]);
  }

  // Brings a cell coordinate c outside the grid back in through a periodic face, with the image
  // shift (-1 or +1 box lengths) it is seen through; false beyond a walled face.
  bool wrap(const PeriodicBox& box, int axis, int& c, int& shift) const {
    if (c >= 0 && c < cells_[axis]) return true;
    if (!box.periodic[axis]) return false;
    shift = c < 0 ? -1 : 1;
    c -= shift * cells_[axis];
    return true;
  }

  // Calls visit(cell, shift, shift_velocity, x_images) for each cell around cell coordinates c
  // (3 x 3 x 3 in 3D, 3 x 3 in 2D; none beyond a walled face), with the shift of the periodic
  // image it is seen through and that image's velocity: images across x move at `width_rate` (a
  // Couette cell whose width follows its gap), and across a Lees–Edwards boundary (at time `now`)
  // a whole sliding row is visited, with `x_images` set. Inlined into the engine's prediction.
  template <class Nodes, class Visit>
  [[gnu::always_inline]] void for_each_cell_around(const PeriodicBox& box, const std::array<int, 3>& c,
                                                   const Nodes& nodes, const LeesEdwardsImages& images, double now,
                                                   double width_rate, Visit&& visit) const {
    // The neighboring cells are listed first and the first particle of each fetched ahead, so the
    // memory reads for all of them overlap instead of following one another.
    struct Around {
      int cell, sx, sy, sz;
    };
    std::array<Around, 27> around;
    int count = 0;
    const int span_z = Dim == 3 ? 1 : 0;
    for (int dz = -span_z; dz <= span_z; ++dz) {
      int cz = c[2] + dz, sz = 0;
      if (!wrap(box, 2, cz, sz)) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        int cy = c[1] + dy, sy = 0;
        if (!wrap(box, 1, cy, sy)) continue;
        if (sy != 0 && images.sliding()) {
          // Across a Lees–Edwards boundary the image row slides: its x offset is sy * delta(t) and
          // it moves at sy * U. Every cell of that row is searched, so no partner is missed.
          const Vec3 shift{sy * images.offset(box.length(0), now), sy * box.length(1), sz * box.length(2)};
          const Vec3 shift_velocity{sy * images.shear_velocity, 0.0, 0.0};
          for (int cx = 0; cx < cells_[0]; ++cx) visit(index(cx, cy, cz), shift, shift_velocity, true);
          continue;
        }
        for (int dx = -1; dx <= 1; ++dx) {
          int cx = c[0] + dx, sx = 0;
          if (!wrap(box, 0, cx, sx)) continue;
          around[count++] = {index(cx, cy, cz), sx, sy, sz};
        }
      }
    }
    for (int k = 0; k < count; ++k)
      if (const int first = head_[around[k].cell]; first >= 0) __builtin_prefetch(&nodes[first]);
    for (int k = 0; k < count; ++k) {
      const Around& a = around[k];
      const Vec3 shift{a.sx * box.length(0), a.sy * box.length(1), a.sz * box.length(2)};
      const Vec3 shift_velocity{a.sx * width_rate, 0.0, 0.0};  // images move with the width rate
      visit(a.cell, shift, shift_velocity, false);
    }
  }

  // When a particle in the cell at coordinates c, at x moving at v and accelerating at `acc`,
  // reaches a face of its cell (the box's walled faces aside): kNever if never; `face` = axis * 2
  // + 1 for the upper face, + 0 for the lower. Faces along x stretch with the periodic width
  // (`width_rate`, the Couette servo); elsewhere they stand still.
  double exit_time(const PeriodicBox& box, const std::array<int, 3>& c, const Vec3& x, const Vec3& v, const Vec3& acc,
                   double width_rate, int& face) const {
    double best = kNever;
    for (int a = 0; a < Dim; ++a) {
      const bool periodic = box.periodic[a];
      if (cells_[a] == 1 && !periodic) continue;
      const double face_lo = box.lo[a] + c[a] * cell_size_[a];
      const double face_hi = c[a] + 1 == cells_[a] ? box.hi[a] : face_lo + cell_size_[a];
      const double rate_lo = a == 0 ? width_rate * c[a] / cells_[a] : 0.0;
      const double rate_hi = a == 0 ? width_rate * (c[a] + 1) / cells_[a] : 0.0;
      if (c[a] > 0 || periodic) {
        const double t = closing_time(x[a] - face_lo, v[a] - rate_lo, acc[a]);
        if (t < best) {
          best = t;
          face = a * 2;
        }
      }
      if (c[a] + 1 < cells_[a] || periodic) {
        const double t = closing_time(face_hi - x[a], rate_hi - v[a], -acc[a]);
        if (t < best) {
          best = t;
          face = a * 2 + 1;
        }
      }
    }
    return best;
  }

  // The periodic width changed (a Couette cell whose width follows its gap): cells stretch with it.
  void stretch_x(const PeriodicBox& box) { cell_size_[0] = box.length(0) / cells_[0]; }

  // Files particle i in `cell`, at the head of its list.
  template <class Nodes>
  void insert(Nodes& nodes, int i, int cell) {
    cell_[i] = cell;
    prev_[i] = -1;
    nodes[i].next = head_[cell];
    if (head_[cell] >= 0) prev_[head_[cell]] = i;
    head_[cell] = i;
  }
  template <class Nodes>
  void move(Nodes& nodes, int i, int cell) {
    unlink(nodes, i);
    insert(nodes, i, cell);
  }
  // Files i in `cell` without linking it: the list path's rebuilds read only the cell (the lists
  // were last walked when the particles were sorted).
  void file(int i, int cell) { cell_[i] = cell; }

 private:
  template <class Nodes>
  void unlink(Nodes& nodes, int i) {
    if (prev_[i] >= 0) nodes[prev_[i]].next = nodes[i].next;
    else head_[cell_[i]] = nodes[i].next;
    if (nodes[i].next >= 0) prev_[nodes[i].next] = prev_[i];
  }

  std::array<int, 3> cells_{1, 1, 1};
  Vec3 cell_size_;                // m
  std::vector<int> head_;         // per cell
  std::vector<int> prev_, cell_;  // per particle
};

}  // namespace grainflow::edmd
