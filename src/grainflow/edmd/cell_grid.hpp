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

  int count(int axis) const { return cells_[axis]; }      // cells along an axis
  double width(int axis) const { return cell_size_[axis]; }  // m
  std::size_t size() const { return head_.size(); }       // cells in all
  int head(int cell) const { return head_[cell]; }        // first particle in a cell, -1 when empty
  int cell(int i) const { return cell_[i]; }               // the cell particle i is filed in

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
  Vec3 cell_size_;         // m
  std::vector<int> head_;  // per cell
  std::vector<int> prev_, cell_;  // per particle
};

}  // namespace grainflow::edmd
