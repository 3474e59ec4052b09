// The event-driven engine's neighbour lists (its fast path). Without gravity, Lees–Edwards
// boundaries or a servo-controlled width every particle flies in a straight line, and each one
// keeps a list of the particles that it can meet: particle i stays within `shell` of its list
// centre c_i (its position when the list was built) until an "expiry" event, when its list is
// rebuilt around where it is then. Two particles whose centres lie more than r_i + r_j + 2 shell
// apart cannot touch before one of them expires, so i looks for collisions with its list only
// (about a third of the 27 cells' particles) and crosses no cells. Lists are symmetric: rebuilding
// i's list removes i from its old neighbours' lists and adds it to its new ones', so a pair is
// always seen by whichever of the two changes course first. The cell grid (cells >= max diameter +
// 2 shell) holds the particles by centre, for rebuilds only: each cell keeps its particles' centres
// in "slots", side by side in single precision, so that a rebuild tests eight at once.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#if defined(__AVX__)
#include <immintrin.h>
#endif
#include <new>
#include <numbers>
#include <span>
#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"
#include "grainflow/edmd/cell_grid.hpp"
#include "grainflow/edmd/free_flight.hpp"

namespace grainflow::edmd {

template <int Dim>
class NeighborLists {
 public:
  template <class Archive>
  void serialize(Archive& ar) {
    ar(center_, inside_, list_, list_cap_, slot_x_, slot_id_, slot_count_, slot_of_, slot_cap_);
    kept_.resize(list_cap_);  // scratch, sized with the lists and slots
    found_.resize(slot_cap_);
  }

  // The shell trades rebuilds (each scans 27 cells of side d + 2 shell) against longer lists
  // (scanned at every prediction): measured best near 0.3 d at packing 0.47 and 0.45 d at 0.26 (N =
  // 32,000), about 0.2 d plus half the mean free path 1 / (sqrt 2 pi n d^2) (3D) or 1 / (2 sqrt 2 n d)
  // (2D). Returns the shell in diameters.
  static double shell_fraction(const PeriodicBox& box, std::size_t particles, double max_diameter) {
    double volume = 1.0;
    for (int a = 0; a < Dim; ++a) volume *= box.length(a);
    const double n = static_cast<double>(particles) / volume;
    const double d = max_diameter;
    const double free_path =
        Dim == 3 ? 1.0 / (std::sqrt(2.0) * std::numbers::pi * n * d * d) : 1.0 / (2.0 * std::sqrt(2.0) * n * d);
    return std::clamp(0.2 + 0.5 * free_path / d, 0.2, 0.6);
  }

  // The shell and periods for `particles` particles in `box` (largest diameter `max_diameter`; one
  // radius `uniform_radius`, or 0 when sizes differ). False where lists cannot serve this box.
  bool configure(const PeriodicBox& box, std::size_t particles, double max_diameter, double uniform_radius) {
    max_diameter_ = max_diameter;
    uniform_radius_ = uniform_radius;
    shell_ = shell_fraction(box, particles, max_diameter) * max_diameter;
    if (!(shell_ > 0.0)) return false;
    for (int a = 0; a < 3; ++a) {
      period_[a] = inv_period_[a] = 0.0;
      if (a < Dim && box.periodic[a]) {
        // Three cells per periodic axis: the 27 searched cells are distinct and the nearest image
        // of any two particles within reach of each other is unique.
        if (box.length(a) < 3.0 * cell_width()) return false;
        period_[a] = box.length(a);
        inv_period_[a] = 1.0 / box.length(a);
      }
    }
    return true;
  }

  double shell() const { return shell_; }  // m
  // The grid's cell width on the list path: every centre within reach of i's lies in the 27 cells around i's.
  double cell_width() const { return max_diameter_ + 2.0 * shell_ * (1.0 + 1e-9); }

  // Every particle's list, around its position now (`nodes[i].x`, in the box): `grid` holds them
  // by those positions; `radius` is read only when sizes differ.
  template <class Nodes>
  void build(const PeriodicBox& box, const CellGrid<Dim>& grid, const Nodes& nodes, const std::vector<double>& radius) {
    const std::size_t n = nodes.size();
    center_.resize(n);
    for (std::size_t i = 0; i < n; ++i) center_[i] = nodes[i].x;
    inside_.resize(n);
    for (std::size_t i = 0; i < n; ++i) inside_[i] = far_from_faces(box, static_cast<std::uint32_t>(i));
    slot_cap_ = 8;
    // Coordinates within [-shell, L + shell) rounded to float: each off by 2^-24 of that at most.
    double extent = 0.0;
    for (int a = 0; a < Dim; ++a) extent = std::max(extent, box.length(a) + shell_);
    // Distances are also taken in single precision: a margin of 1e-6 of the extent covers both.
    slot_rounding_ = 1e-6 * (extent + 2.0 * max_diameter_);
    found_.resize(slot_cap_);
    slot_count_.assign(grid.size(), 0);
    slot_x_.assign(grid.size() * slot_cap_ * 3, kFarSlot);
    slot_id_.assign(grid.size() * slot_cap_, 0);
    slot_of_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) insert_slot(box, grid, static_cast<std::uint32_t>(i));
    list_cap_ = 16;
    list_.assign(n * list_cap_, 0);
    kept_.resize(list_cap_);
    for (std::size_t i = 0; i < n; ++i)
      search_neighbors(box, grid, radius, static_cast<std::uint32_t>(i), [&](std::uint32_t j) {
        if (j > i) {
          push_neighbor(static_cast<std::uint32_t>(i), j);
          push_neighbor(j, static_cast<std::uint32_t>(i));
        }
      });
  }

  // Particle i has reached the edge of its shell: a new list around x, where it is now (in the box).
  void rebuild(std::uint32_t i, const Vec3& x, const PeriodicBox& box, CellGrid<Dim>& grid,
               const std::vector<double>& radius) {
    // Old neighbours forget i (their lists fetched together, not one miss after another).
    std::uint32_t* mine = list_of(i);
    for (std::uint32_t k = 1; k <= mine[0]; ++k) __builtin_prefetch(list_of(mine[k]), 1);
    for (std::uint32_t k = 1; k <= mine[0]; ++k) {
      std::uint32_t* theirs = list_of(mine[k]);
      const std::uint32_t m = find_in_list(theirs, i);
      theirs[m] = theirs[theirs[0]--];
    }
    mine[0] = 0;
    remove_slot(grid, i);
    center_[i] = x;
    grid.file(static_cast<int>(i), grid.cell_of(box, center_[i]));
    inside_[i] = far_from_faces(box, i);
    insert_slot(box, grid, i);
    search_neighbors(box, grid, radius, i, [&](std::uint32_t j) {
      __builtin_prefetch(list_of(j), 1);
      push_neighbor(i, j);
    });
    for (std::uint32_t k = 1; k <= list_of(i)[0]; ++k) push_neighbor(list_of(i)[k], i);
  }

  // The particles i can meet before its list expires.
  std::span<const std::uint32_t> neighbors(std::uint32_t i) const { return {list_of(i) + 1, list_of(i)[0]}; }

  // True when no particle that i can meet is seen through a periodic face (as of i's last rebuild):
  // separations need no nearest-image rounding.
  bool sees_no_images(std::uint32_t i) const { return inside_[i] != 0; }

  // Nearest periodic image of a separation (no-op along walled axes and z in 2D).
  Vec3 nearest(Vec3 d) const {
    for (int a = 0; a < Dim; ++a) d[a] -= period_[a] * std::nearbyint(d[a] * inv_period_[a]);
    return d;
  }

  // The list path's common case, equal spheres all flying straight: the listed neighbour that i, at
  // xi moving at vi `now`, touches first before `best` (which then becomes that time), or kNone.
  // `nodes` are the particles' flights (x and v at their own clocks). Two passes: the first,
  // without branches on the (random) signs, keeps the neighbours that approach and could touch
  // before the best time so far (the test of contact_time_before(), against the shell expiry); the
  // second solves the few kept exactly. Inlined into the engine's prediction.
  static constexpr std::uint32_t kNone = ~0u;
  template <class Nodes>
  [[gnu::always_inline]] std::uint32_t first_contact(std::uint32_t i, const Nodes& nodes, const Vec3& xi,
                                                     const Vec3& vi, double now, double& best) {
    const std::uint32_t* list = list_of(i) + 1;
    const std::uint32_t count = list[-1];
    const bool inside = inside_[i] != 0;
    auto separation = [&](const auto& fj) {
      const Vec3 xj = fj.x + (now - fj.clock) * fj.v;
      return inside ? xi - xj : nearest(xi - xj);
    };
    const double speed_i = norm(vi);
    const double sigma2 = 4.0 * uniform_radius_ * uniform_radius_;
    const double horizon = -2.0 * best * (1.0 + 1e-9);
    std::uint32_t* kept = kept_.data();  // list_cap_ long
    std::uint32_t m = 0;
    for (std::uint32_t k = 0; k < count; ++k) {
      const auto& fj = nodes[list[k]];
      const Vec3 d = separation(fj);
      const double b = dot(d, vi - fj.v);
      const double c = norm2(d) - sigma2;
      kept[m] = list[k];
      m += (b < 0.0) & (c <= b * horizon);
    }
    std::uint32_t first = kNone;
    for (std::uint32_t q = 0; q < m; ++q) {
      const std::uint32_t j = kept[q];
      const auto& fj = nodes[j];
      auto floor = [&] { return kVelocityResolution * (speed_i + norm(fj.v)); };
      const double t = contact_time_before(separation(fj), vi - fj.v, 2.0 * uniform_radius_, best, floor);
      if (t < best) {
        best = t;
        first = j;
      }
    }
    return first;
  }

  // Time until i, at xi moving at vi, is a shell away from its list centre (0 when it already is,
  // kNever at rest): |d + v t| = shell, with d = x_i - c_i inside the shell, the positive root.
  double expiry_time(std::uint32_t i, const Vec3& xi, const Vec3& vi) const {
    const Vec3 d = nearest(xi - center_[i]);
    const double c = norm2(d) - shell_ * shell_;
    const double b = dot(d, vi);
    const double a = norm2(vi);
    if (c >= 0.0) return 0.0;
    if (a == 0.0) return kNever;
    const double root = std::sqrt(b * b - a * c);
    return b > 0.0 ? -c / (b + root) : (root - b) / a;
  }

 private:
  double radius_of(const std::vector<double>& radius, std::uint32_t j) const {
    return uniform_radius_ > 0.0 ? uniform_radius_ : radius[j];
  }

  // Calls found(j) for every other particle whose centre lies within reach of i's (and perhaps a
  // few just beyond: the cells keep centres in single precision and distances are taken in it, so
  // the reach has a margin for their rounding). Each cell keeps its particles' centres side by side,
  // x, y and z each in a row of slot_cap_ floats (unused slots far away), so that eight are tested
  // at once; a periodic neighbour cell is seen through its shift.
  template <class Found>
  void search_neighbors(const PeriodicBox& box, const CellGrid<Dim>& grid, const std::vector<double>& radius,
                        std::uint32_t i, Found&& found) {
    const Vec3 ci = center_[i] - box.lo;
    const double ri = radius_of(radius, i);
    const double skin = 2.0 * shell_ * (1.0 + 1e-9) + slot_rounding_;
    const double uniform_reach = 2.0 * uniform_radius_ + skin;
    const float reach2 = static_cast<float>(uniform_reach * uniform_reach);
    const auto c = grid.coordinates(grid.cell(static_cast<int>(i)));
    const int span_z = Dim == 3 ? 1 : 0;
    const std::size_t cap = slot_cap_;
    for (int dz = -span_z; dz <= span_z; ++dz) {
      int cz = c[2] + dz, sz = 0;
      if (!grid.wrap(box, 2, cz, sz)) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        int cy = c[1] + dy, sy = 0;
        if (!grid.wrap(box, 1, cy, sy)) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          int cx = c[0] + dx, sx = 0;
          if (!grid.wrap(box, 0, cx, sx)) continue;
          // ci - (cj + shift) = (ci - shift) - cj
          const Vec3 from{ci.x - sx * period_[0], ci.y - sy * period_[1], ci.z - sz * period_[2]};
          const std::size_t cell = static_cast<std::size_t>(grid.index(cx, cy, cz));
          const float* x = &slot_x_[cell * cap * 3];
          const std::uint32_t* id = &slot_id_[cell * cap];
          const std::uint32_t count = slot_count_[cell];
          if (uniform_radius_ > 0.0) {
#if defined(__AVX__)
            const __m256 fx = _mm256_set1_ps(static_cast<float>(from.x)),
                         fy = _mm256_set1_ps(static_cast<float>(from.y)),
                         fz = _mm256_set1_ps(static_cast<float>(from.z)), r2 = _mm256_set1_ps(reach2);
            for (std::uint32_t k = 0; k < count; k += 8) {
              const __m256 ex = _mm256_sub_ps(fx, _mm256_loadu_ps(x + k));
              const __m256 ey = _mm256_sub_ps(fy, _mm256_loadu_ps(x + cap + k));
              const __m256 ez = _mm256_sub_ps(fz, _mm256_loadu_ps(x + 2 * cap + k));
              const __m256 d2 =
                  _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ex, ex), _mm256_mul_ps(ey, ey)), _mm256_mul_ps(ez, ez));
              for (unsigned bits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(d2, r2, _CMP_LT_OQ)));
                   bits != 0; bits &= bits - 1) {
                const std::uint32_t j = id[k + static_cast<std::uint32_t>(__builtin_ctz(bits))];
                if (j != i) found(j);
              }
            }
#else
            std::uint32_t* near = found_.data();  // without branches on the (random) outcome
            std::uint32_t m = 0;
            const float gx = static_cast<float>(from.x), gy = static_cast<float>(from.y),
                        gz = static_cast<float>(from.z);
            for (std::uint32_t k = 0; k < count; ++k) {
              const float ex = gx - x[k], ey = gy - x[cap + k], ez = gz - x[2 * cap + k];
              near[m] = id[k];
              m += (ex * ex + ey * ey + ez * ez < reach2) & (id[k] != i);
            }
            for (std::uint32_t q = 0; q < m; ++q) found(near[q]);
#endif
            continue;
          }
          for (std::uint32_t k = 0; k < count; ++k) {
            const Vec3 d{from.x - x[k], from.y - x[cap + k], from.z - x[2 * cap + k]};
            const double reach = ri + radius_of(radius, id[k]) + skin;
            if (norm2(d) < reach * reach && id[k] != i) found(id[k]);
          }
        }
      }
    }
  }

  void insert_slot(const PeriodicBox& box, const CellGrid<Dim>& grid, std::uint32_t i) {
    const std::size_t cell = static_cast<std::size_t>(grid.cell(static_cast<int>(i)));
    if (slot_count_[cell] == slot_cap_) grow_slots();
    const std::uint32_t k = slot_count_[cell]++;
    const Vec3 c = center_[i] - box.lo;
    float* x = &slot_x_[cell * slot_cap_ * 3];
    x[k] = static_cast<float>(c.x);
    x[slot_cap_ + k] = static_cast<float>(c.y);
    x[2 * slot_cap_ + k] = static_cast<float>(c.z);
    slot_id_[cell * slot_cap_ + k] = i;
    slot_of_[i] = k;
  }

  void remove_slot(const CellGrid<Dim>& grid, std::uint32_t i) {
    const std::size_t cell = static_cast<std::size_t>(grid.cell(static_cast<int>(i)));
    float* x = &slot_x_[cell * slot_cap_ * 3];
    std::uint32_t* id = &slot_id_[cell * slot_cap_];
    const std::uint32_t last = --slot_count_[cell], k = slot_of_[i];
    for (std::size_t a = 0; a < 3; ++a) {
      x[a * slot_cap_ + k] = x[a * slot_cap_ + last];
      x[a * slot_cap_ + last] = kFarSlot;
    }
    id[k] = id[last];
    slot_of_[id[k]] = k;
  }

  void grow_slots() {
    const std::size_t cells = slot_count_.size(), cap = slot_cap_ + 8;
    std::vector<float> wider_x(cells * cap * 3, kFarSlot);
    std::vector<std::uint32_t> wider_id(cells * cap, 0);
    for (std::size_t c = 0; c < cells; ++c) {
      for (std::size_t a = 0; a < 3; ++a)
        std::copy_n(slot_x_.begin() + static_cast<std::ptrdiff_t>((c * 3 + a) * slot_cap_), slot_count_[c],
                    wider_x.begin() + static_cast<std::ptrdiff_t>((c * 3 + a) * cap));
      std::copy_n(slot_id_.begin() + static_cast<std::ptrdiff_t>(c * slot_cap_), slot_count_[c],
                  wider_id.begin() + static_cast<std::ptrdiff_t>(c * cap));
    }
    slot_x_.swap(wider_x);
    slot_id_.swap(wider_id);
    slot_cap_ = cap;
    found_.resize(cap);
  }

  // A list is list_cap_ words (a 64-byte line at first): its length, then the neighbours.
  std::uint32_t* list_of(std::uint32_t i) { return list_.data() + static_cast<std::size_t>(i) * list_cap_; }
  const std::uint32_t* list_of(std::uint32_t i) const { return list_.data() + static_cast<std::size_t>(i) * list_cap_; }

  // True when i's centre lies so far inside the box along every periodic axis that no particle it
  // can meet is seen through a periodic face: a neighbour's centre is within reach (< 2 max radius
  // + 2 shell) of i's, and any particle strays at most a shell from its centre (the engine's
  // synchronize() may wrap one that strayed across a face, which needs its centre within a shell
  // of that face).
  bool far_from_faces(const PeriodicBox& box, std::uint32_t i) const {
    const double margin = (max_diameter_ + 4.0 * shell_) * (1.0 + 1e-6);
    for (int a = 0; a < Dim; ++a)
      if (period_[a] != 0.0 && (center_[i][a] - box.lo[a] < margin || box.hi[a] - center_[i][a] < margin)) return false;
    return true;
  }

  void push_neighbor(std::uint32_t i, std::uint32_t j) {
    if (list_of(i)[0] + 1 == list_cap_) grow_lists();
    std::uint32_t* list = list_of(i);
    list[++list[0]] = j;
  }

  void grow_lists() {
    const std::size_t n = center_.size(), cap = 2 * list_cap_;
    AlignedWords wider(n * cap);
    for (std::size_t i = 0; i < n; ++i)
      std::copy_n(list_.begin() + static_cast<std::ptrdiff_t>(i * list_cap_), list_[i * list_cap_] + 1,
                  wider.begin() + static_cast<std::ptrdiff_t>(i * cap));
    list_.swap(wider);
    list_cap_ = cap;
    kept_.resize(cap);
  }

  // Where j sits in `list` (it must be there), eight words compared at a time where AVX2 is: the
  // first match past the length word is j's entry, as words past the end come after it.
  std::uint32_t find_in_list(const std::uint32_t* list, std::uint32_t j) const {
#if defined(__AVX2__)
    const __m256i key = _mm256_set1_epi32(static_cast<int>(j));
    unsigned skip = 1;  // the length word
    for (std::uint32_t base = 0;; base += 8, skip = 0) {
      const __m256i words = _mm256_load_si256(reinterpret_cast<const __m256i*>(list + base));
      const unsigned hits =
          static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(words, key)))) & ~skip;
      if (hits != 0) return base + static_cast<std::uint32_t>(__builtin_ctz(hits));
    }
#else
    std::uint32_t m = 1;
    while (list[m] != j) ++m;
    return m;
#endif
  }

  template <class T>
  struct LineAllocator {  // 64-byte aligned storage, so each list starts on a cache line
    using value_type = T;
    LineAllocator() = default;
    template <class U>
    LineAllocator(const LineAllocator<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64})); }
    void deallocate(T* p, std::size_t) { ::operator delete (p, std::align_val_t{64}); }
    bool operator==(const LineAllocator&) const { return true; }
  };
  using AlignedWords = std::vector<std::uint32_t, LineAllocator<std::uint32_t>>;

  double max_diameter_ = 0.0;         // m
  double uniform_radius_ = 0.0;       // m, the radius of every particle, or 0 when sizes differ
  double shell_ = 0.0;                // m, how far a particle moves from its list centre before a rebuild
  Vec3 period_, inv_period_;          // box lengths along periodic axes (0 elsewhere) and inverses
  std::vector<Vec3> center_;          // list centres
  std::vector<std::uint8_t> inside_;  // far_from_faces() at the last rebuild
  std::vector<std::uint32_t> kept_;   // first_contact()'s scratch: the neighbours worth solving for
  AlignedWords list_;                 // list_cap_ words per particle: count, then neighbours
  std::size_t list_cap_ = 0;
  double slot_rounding_ = 0.0;  // m, bound on the error of a distance between centres in slots
  // Per cell, slot_cap_ (a multiple of 8) slots: list centres from the box's low corner in single
  // precision, rows of x, y and z, and the particles' indices; unused slots lie far away.
  static constexpr float kFarSlot = 1e18f;
  std::vector<float> slot_x_;
  std::vector<std::uint32_t> slot_id_;
  std::vector<std::uint32_t> slot_count_, slot_of_;
  std::size_t slot_cap_ = 0;
  std::vector<std::uint32_t> found_;  // search_neighbors()' scratch, slot_cap_ long
};

}  // namespace grainflow::edmd
