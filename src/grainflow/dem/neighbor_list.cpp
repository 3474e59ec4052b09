#include "grainflow/dem/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "grainflow/core/cell_counts.hpp"
#include "grainflow/dem/thread_slices.hpp"

namespace grainflow::dem {

void CellGrid::setup(const PeriodicBox& box, double cell_size, std::size_t particles) {
  setup_region(box, box.lo, box.hi, {false, false, false}, cell_size, particles);
}

void CellGrid::setup_region(const PeriodicBox& box, const Vec3& lo, const Vec3& hi, const std::array<bool, 3>& cut,
                            double cell_size, std::size_t particles) {
  box_ = box;
  std::array<double, 3> lengths{};
  for (int axis = 0; axis < 3; ++axis) {
    lo_[axis] = cut[axis] ? lo[axis] : box.lo[axis];
    lengths[axis] = cut[axis] ? hi[axis] - lo[axis] : box.length(axis);
    wraps_[axis] = box.periodic[axis] && !cut[axis];
    framed_[axis] = box.periodic[axis] && cut[axis];
  }
  cells_ = cell_counts(lengths, 3, cell_size, 1 << 12, std::max(32768.0, 4.0 * static_cast<double>(particles)));
  for (int axis = 0; axis < 3; ++axis) {
    inv_size_[axis] = cells_[axis] / lengths[axis];
    // One cell across a wrapping axis: the partner's images up to a cutoff away, one box length
    // per step (the case checks keep a width of at least half a cutoff: kMaxImage steps).
    reach_[axis] = 1;
    if (wraps_[axis] && cells_[axis] == 1)
      reach_[axis] =
          std::clamp(static_cast<int>(std::ceil(cell_size / lengths[axis] - 1e-12)), 1, PeriodicBox::kMaxImage);
  }
  // The sliding rows' search takes four distinct cells along x and three along y (the case checks
  // keep those widths; the guard is for a grid widened to bound its cell count).
  if (box.sheared() && (cells_[0] < 4 || cells_[1] < 3 || cut[0] || cut[1]))
    throw std::logic_error("CellGrid: Lees-Edwards boundaries need 4 cells along x and 3 along y on one rank");
}

int CellGrid::cell_of(const Vec3& x) const {
  int c[3];
  for (int axis = 0; axis < 3; ++axis) {
    int k = static_cast<int>(std::floor((x[axis] - lo_[axis]) * inv_size_[axis]));
    c[axis] = std::clamp(k, 0, cells_[axis] - 1);
  }
  return c[0] + cells_[0] * (c[1] + cells_[1] * c[2]);
}

void CellGrid::bin(const std::vector<Vec3>& position) {
  const std::size_t n = position.size();
  const std::size_t total = static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2];
  const bool framed = framed_[0] || framed_[1] || framed_[2];
  frame_.assign(framed ? n : 0, {0, 0, 0});
  start_.assign(total + 1, 0);
  cell_index_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 x = position[i];
    if (framed)
      for (int axis = 0; axis < 3; ++axis) {
        if (!framed_[axis]) continue;
        // The image nearest the region: its centre is within half a box length of it.
        const double length = box_.length(axis);
        const double centre = lo_[axis] + 0.5 * cells_[axis] / inv_size_[axis];
        const int k = static_cast<int>(std::nearbyint((centre - x[axis]) / length));
        frame_[i][axis] = static_cast<std::int8_t>(std::clamp(k, -1, 1));
        x[axis] += frame_[i][axis] * length;
      }
    cell_index_[i] = cell_of(x);
    ++start_[cell_index_[i] + 1];
  }
  for (std::size_t c = 0; c < total; ++c) start_[c + 1] += start_[c];
  order_.resize(n);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) order_[fill[cell_index_[i]]++] = static_cast<std::uint32_t>(i);
}

// Pairs of particles [begin, end) with partners of a higher id in the 27 cells around each (more
// images along a narrow periodic axis, and the particle's own images). Framed: along cut periodic
// axes the particles sit at their images frame_[i] inside the region, and a pair's shift code adds
// the difference of the two images.
template <bool Framed, bool Wide>
void CellGrid::search(const ParticleStore& p, const PeriodicBox& box, double skin, std::size_t begin, std::size_t end,
                      std::vector<std::uint32_t>& my_partners, std::vector<std::uint8_t>& my_codes,
                      std::vector<std::uint32_t>& my_counts) const {
  const Vec3 length{box.length(0), box.length(1), box.length(2)};
  for (std::size_t i = begin; i < end; ++i) {
    const int cell = cell_index_[i];
    const int ci[3] = {cell % cells_[0], (cell / cells_[0]) % cells_[1], cell / (cells_[0] * cells_[1])};
    Vec3 xi = p.position[i];
    if constexpr (Framed)
      for (int a = 0; a < 3; ++a) xi[a] += frame_[i][a] * length[a];
    const double ri = p.target_radius[i] + skin;
    const std::uint32_t idi = p.id[i];
    const std::size_t before = my_partners.size();
    // Neighbour cell c + d along an axis: inside, or wrapped to an image s box lengths away.
    auto wrap = [&](int axis, int c, int& s) {
      s = 0;
      const int n = cells_[axis];
      if (c >= 0 && c < n) return c;
      if (!wraps_[axis]) return -1;
      if constexpr (Wide) s = c >= 0 ? c / n : -((n - 1 - c) / n);  // floor(c / n) in integers
      else s = c < 0 ? -1 : 1;
      return c - s * n;
    };
    const int reach_x = Wide ? reach_[0] : 1, reach_y = Wide ? reach_[1] : 1, reach_z = Wide ? reach_[2] : 1;
    for (int dz = -reach_z; dz <= reach_z; ++dz) {
      int sz = 0;
      const int cz = wrap(2, ci[2] + dz, sz);
      if (cz < 0) continue;
      for (int dy = -reach_y; dy <= reach_y; ++dy) {
        int sy = 0;
        const int cy = wrap(1, ci[1] + dy, sy);
        if (cy < 0) continue;
        // Across a Lees–Edwards seam the row of cells stands offset along x: the four cells under
        // [x_i - offset - cell, x_i - offset + cell] hold every image within reach.
        int first_x = ci[0] - reach_x, last_x = ci[0] + reach_x;
        double row_offset = 0.0;
        if (Wide && sy != 0 && box.sheared()) {
          row_offset = sy * box.shear_offset;
          first_x = static_cast<int>(std::floor(ci[0] - row_offset * inv_size_[0])) - 1;
          last_x = first_x + 3;
        }
        for (int cx_raw = first_x; cx_raw <= last_x; ++cx_raw) {
          int sx = 0;
          const int cx = wrap(0, cx_raw, sx);
          if (cx < 0) continue;
          const Vec3 shift{sx * length[0] + row_offset, sy * length[1], sz * length[2]};
          const std::uint8_t code = PeriodicBox::shift_code(sx, sy, sz);
          const int neighbor = cx + cells_[0] * (cy + cells_[1] * cz);
          for (std::uint32_t k = start_[neighbor]; k < start_[neighbor + 1]; ++k) {
            const std::uint32_t j = order_[k];
            // Each pair once: a partner of higher id, or one's own image in the positive direction.
            if (p.id[j] <= idi && (p.id[j] < idi || j != i || code <= PeriodicBox::kNoShift)) continue;
            if (!pair_interacts(p, i, j)) continue;
            Vec3 xj = p.position[j] + shift;
            if constexpr (Framed)
              for (int a = 0; a < 3; ++a) xj[a] += frame_[j][a] * length[a];
            const Vec3 d = xi - xj;
            const double cutoff = ri + p.target_radius[j];
            if (norm2(d) < cutoff * cutoff) {
              my_partners.push_back(j);
              if constexpr (Framed)  // x_i - x_j at the images = x_i - (x_j + (s + f_j - f_i) L)
                my_codes.push_back(PeriodicBox::shift_code(sx + frame_[j][0] - frame_[i][0],
                                                           sy + frame_[j][1] - frame_[i][1],
                                                           sz + frame_[j][2] - frame_[i][2]));
              else my_codes.push_back(code);
            }
          }
        }
      }
    }
    my_counts[i - begin] = static_cast<std::uint32_t>(my_partners.size() - before);
  }
}

void CellGrid::build_pairs(const ParticleStore& p, const PeriodicBox& box, double skin, int threads, NeighborPairs& out,
                           std::size_t expected_pairs) const {
  const std::size_t n = p.size();
  threads = std::max(1, threads);
  struct SliceLists {  // one thread's: partners and their image codes, and the count per particle
    std::vector<std::uint32_t> partners, counts;
    std::vector<std::uint8_t> codes;
  };
  std::vector<ThreadSlot<SliceLists>> lists(threads);  // a thread's push_backs stay on its own lines
  const bool wide = box.sheared() || reach_ != std::array<int, 3>{1, 1, 1};

  for_each_slice(threads, n, [&](int t, std::size_t begin, std::size_t end) {
    SliceLists& mine = lists[t].value;
    mine.counts.assign(end - begin, 0);
    mine.partners.reserve(expected_pairs / threads + expected_pairs / threads / 16);  // + 6 %: lists vary
    mine.codes.reserve(mine.partners.capacity());
    const bool framed = !frame_.empty();
    if (framed && wide) search<true, true>(p, box, skin, begin, end, mine.partners, mine.codes, mine.counts);
    else if (framed) search<true, false>(p, box, skin, begin, end, mine.partners, mine.codes, mine.counts);
    else if (wide) search<false, true>(p, box, skin, begin, end, mine.partners, mine.codes, mine.counts);
    else search<false, false>(p, box, skin, begin, end, mine.partners, mine.codes, mine.counts);
  });

  out.offsets.assign(n + 1, 0);
  std::size_t total = 0;
  for (const auto& slot : lists) total += slot.value.partners.size();
  out.partner.resize(total);
  out.shift.resize(total);
  std::size_t cursor = 0, i = 0;
  for (auto& slot : lists) {
    SliceLists& l = slot.value;
    std::copy(l.partners.begin(), l.partners.end(), out.partner.begin() + cursor);
    std::copy(l.codes.begin(), l.codes.end(), out.shift.begin() + cursor);
    cursor += l.partners.size();
    std::vector<std::uint32_t>().swap(l.partners);  // freed as it goes: the peak holds about one list
    std::vector<std::uint8_t>().swap(l.codes);
    for (std::uint32_t c : l.counts) {
      out.offsets[i + 1] = out.offsets[i] + c;
      ++i;
    }
  }
}

void build_pairs_all(const ParticleStore& p, const PeriodicBox& box, double skin, NeighborPairs& out) {
  const std::size_t n = p.size();
  out.offsets.assign(n + 1, 0);
  out.partner.clear();
  out.shift.clear();
  // Every image within reach along the periodic axes: positions lie in the box, so an image s box
  // lengths away is at least (|s| - 1) L away, and ceil(cutoff / L) lengths cover the cutoff.
  double cutoff_max = skin;
  for (std::size_t i = 0; i < n; ++i) cutoff_max = std::max(cutoff_max, 2.0 * p.target_radius[i] + skin);
  int reach[3];
  for (int axis = 0; axis < 3; ++axis)
    reach[axis] = box.periodic[axis] ? std::clamp(static_cast<int>(std::ceil(cutoff_max / box.length(axis))), 1,
                                                  PeriodicBox::kMaxImage)
                                     : 0;
  if (box.sheared()) reach[0] = PeriodicBox::kMaxImage;  // the sliding rows stand up to a width further
  const auto shifts = box.shift_table();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (!pair_interacts(p, i, j)) continue;
      for (int sz = -reach[2]; sz <= reach[2]; ++sz)
        for (int sy = -reach[1]; sy <= reach[1]; ++sy)
          for (int sx = -reach[0]; sx <= reach[0]; ++sx) {
            const std::uint8_t code = PeriodicBox::shift_code(sx, sy, sz);
            if (i == j ? code <= PeriodicBox::kNoShift : p.id[j] <= p.id[i]) continue;
            const Vec3 d = p.position[i] - (p.position[j] + shifts[code]);
            const double cutoff = p.target_radius[i] + p.target_radius[j] + skin;
            if (norm2(d) < cutoff * cutoff) {
              out.partner.push_back(static_cast<std::uint32_t>(j));
              out.shift.push_back(code);
            }
          }
    }
    out.offsets[i + 1] = static_cast<std::uint32_t>(out.partner.size());
  }
}

}  // namespace grainflow::dem
