// Lees–Edwards boundaries in the soft-sphere engine (flow x, gradient y): the image row above stands
// offset by U t along x and moves at U = shear rate x height. A particle leaving through a y face
// enters the sliding row; the cell search finds exactly the images an all-images search finds at
// any offset (also past one width, as between two rebuilds); the engine lists every overlapping
// pair at every step of a sheared gas, under the image the sliding rows give; and contact histories
// survive the seam and the offset's turns (Walton–Braun's largest overlap never falls during a
// contact, while forgetting the histories once makes it fall).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "grainflow/dem/contact_store.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/neighbor_list.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

PeriodicBox sheared_box(double offset, double velocity, std::int32_t turns = 0) {
  PeriodicBox box;
  box.lo = {0.0, 0.0, 0.0};
  box.hi = {10.0, 8.0, 6.0};
  box.periodic = {true, true, true};
  box.shear_offset = offset;
  box.shear_velocity = velocity;
  box.shear_turns = turns;
  return box;
}

// The position of image (sx, sy, sz) of x in a Lees–Edwards lattice of images, written out.
Vec3 image_of(const PeriodicBox& box, const Vec3& x, int sx, int sy, int sz) {
  return {x.x + sx * box.length(0) + sy * box.shear_offset, x.y + sy * box.length(1), x.z + sz * box.length(2)};
}

using PairKey = std::tuple<std::uint32_t, std::uint32_t, int>;  // (smaller id, larger id, shift code)

std::set<PairKey> listed_pairs(const ParticleStore& p, const NeighborPairs& list) {
  std::set<PairKey> out;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::uint32_t k = list.offsets[i]; k < list.offsets[i + 1]; ++k) {
      EXPECT_LT(p.id[i], p.id[list.partner[k]]);
      EXPECT_TRUE(out.emplace(p.id[i], p.id[list.partner[k]], list.shift[k]).second) << "a pair listed twice";
    }
  return out;
}

// Every pair, every image two widths either way along x and one row either way along y.
std::set<PairKey> all_images(const ParticleStore& p, const PeriodicBox& box, double skin) {
  std::set<PairKey> out;
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = 0; b < p.size(); ++b) {
      if (p.id[a] >= p.id[b] || (p.motion[a] != Motion::free && p.motion[b] != Motion::free)) continue;
      const double cutoff = p.target_radius[a] + p.target_radius[b] + skin;
      for (int sz = -1; sz <= 1; ++sz)
        for (int sy = -1; sy <= 1; ++sy)
          for (int sx = -2; sx <= 2; ++sx)
            if (norm2(p.position[a] - image_of(box, p.position[b], sx, sy, sz)) < cutoff * cutoff)
              out.emplace(p.id[a], p.id[b], PeriodicBox::shift_code(sx, sy, sz));
    }
  return out;
}

// The shift code of b's image nearest a under the sliding rows, and the separation to it.
std::uint8_t nearest_image(const PeriodicBox& box, const Vec3& a, const Vec3& b, Vec3& d) {
  d = a - b;
  const int sy = static_cast<int>(std::nearbyint(d.y / box.length(1)));
  d.y -= sy * box.length(1);
  d.x -= sy * box.shear_offset;
  const int sx = static_cast<int>(std::nearbyint(d.x / box.length(0)));
  d.x -= sx * box.length(0);
  const int sz = static_cast<int>(std::nearbyint(d.z / box.length(2)));
  d.z -= sz * box.length(2);
  return PeriodicBox::shift_code(sx, sy, sz);
}

// 120 frictional spheres of two sizes (solids fraction 0.22, T = 30 m^2/s^2) sheared at 2000 1/s:
// the rows slide at 36 m/s, a width every 0.5 ms (~1160 steps of 4.3e-7 s), against thermal speeds
// of ~5 m/s.
const std::string kShearedGas = R"([domain]
lo = [0.0, 0.0, 0.0]
hi = [0.018, 0.018, 0.018]
boundary = { x = "periodic", y = "periodic", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "large"
diameter = 0.003
density = 2490.0
count = 80
[[species]]
name = "small"
diameter = 0.002
density = 2490.0
count = 40
[particles]
init = "lattice"
initial_temperature = 30.0
seed = 5
[contact]
k1 = 1.0e6
restitution = 0.9
friction = 0.5
[lees_edwards]
shear_rate = 2000.0
[run]
duration = 1.0
sort_every = 1
)";

}  // namespace

TEST(DemLeesEdwards, ACrossingParticleEntersTheSlidingRow) {
  const double offset = 3.7, velocity = 16.0;
  const PeriodicBox box = sheared_box(offset, velocity, 2);
  Vec3 x{4.0, 8.5, 1.0}, v{1.0, 2.0, 3.0};
  std::array<std::int32_t, 3> image{0, 0, 0};
  box.wrap(x, image, &v);
  // Up through the top: the row below's image, back by the offset (4 - 3.7 = 0.3), slower by U.
  EXPECT_NEAR(x.x, 0.3, 1e-12);
  EXPECT_NEAR(x.y, 0.5, 1e-12);
  EXPECT_EQ(x.z, 1.0);
  EXPECT_EQ(v.x, 1.0 - velocity);
  EXPECT_EQ(v.y, 2.0);
  EXPECT_EQ(image[1], 1);
  EXPECT_EQ(image[0], -2);  // the turns, so that image keys stay the same
  // Down through the bottom, past the x face: forward by the offset and wrapped along x.
  Vec3 y{8.0, -0.25, 1.0}, w{0.0, 0.0, 0.0};
  std::array<std::int32_t, 3> image_y{0, 0, 0};
  box.wrap(y, image_y, &w);
  EXPECT_NEAR(y.x, 8.0 + offset - 10.0, 1e-12);
  EXPECT_NEAR(y.y, 7.75, 1e-12);
  EXPECT_EQ(w.x, velocity);
  EXPECT_EQ(image_y[1], -1);
  EXPECT_EQ(image_y[0], 2 + 1);

  // minimum_image is the nearest of the written-out images.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 a{10 * u(rng), 8 * u(rng), 6 * u(rng)}, b{10 * u(rng), 8 * u(rng), 6 * u(rng)};
    double nearest = 1e300;
    for (int sz = -1; sz <= 1; ++sz)
      for (int sy = -1; sy <= 1; ++sy)
        for (int sx = -2; sx <= 2; ++sx) nearest = std::min(nearest, norm(a - image_of(box, b, sx, sy, sz)));
    // The convention holds within half the narrowest width (as without shear).
    if (nearest < 2.9) {
      EXPECT_NEAR(norm(box.minimum_image(a, b)), nearest, 1e-12);
    }
  }
}

// The key of a contact (which image of b touches a) must not change when b crosses the seam, nor
// when a rebuild takes a width off the offset (turns + 1): the same physical image, another code.
TEST(DemLeesEdwards, ImageKeysSurviveTheSeamAndTheTurns) {
  const double U = 16.0;
  const Vec3 a{1.0, 0.4, 3.0};
  for (const double offset : {0.0, 2.5, 9.9}) {
    PeriodicBox box = sheared_box(offset, U, 5);
    Vec3 b{1.5 + offset, 7.6, 3.0};  // b's image in the row below stands just under a
    std::array<std::int32_t, 3> ia{0, 0, 0}, ib{4, -2, 1};
    box.wrap(b, ib);
    Vec3 d;
    std::uint8_t code = nearest_image(box, a, b, d);
    ASSERT_LT(norm(d), 1.0);
    const auto key = ContactStore<int>::image_key(code, ia, ib, box.shear_turns);
    // b moves up out of the box: it enters the sliding row.
    Vec3 moved = b + Vec3{0.0, 0.5, 0.0};
    box.wrap(moved, ib);
    Vec3 d_after;
    code = nearest_image(box, a, moved, d_after);
    EXPECT_NEAR(norm(d_after - (d - Vec3{0.0, 0.5, 0.0})), 0.0, 1e-12);
    EXPECT_EQ(ContactStore<int>::image_key(code, ia, ib, box.shear_turns), key) << "offset " << offset;
    // A rebuild takes a width off the offset.
    box.shear_offset -= box.length(0);
    box.shear_turns += 1;
    code = nearest_image(box, a, moved, d_after);
    EXPECT_EQ(ContactStore<int>::image_key(code, ia, ib, box.shear_turns), key) << "offset " << offset << ", turned";
  }
}

TEST(DemLeesEdwards, CellGridFindsExactlyTheAllImagesSet) {
  const double max_radius = 0.5, skin = 0.15;
  // At rest, part of a width, just under one, and 1.3 widths: grown past a width between rebuilds.
  for (const double offset : {0.0, 3.7, 9.999, 13.0, -2.5}) {
    const PeriodicBox box = sheared_box(offset, 1.0);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    ParticleStore p;
    p.resize(500);
    std::vector<std::uint32_t> ids(p.size());
    std::iota(ids.begin(), ids.end(), 0u);
    std::shuffle(ids.begin(), ids.end(), rng);
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.position[i] = {10.0 * u(rng), 8.0 * u(rng), 6.0 * u(rng)};
      if (i % 37 == 0) p.position[i].y = 0.0;  // on the seam
      if (i % 41 == 0) p.position[i].y = std::nextafter(8.0, 0.0);
      p.radius[i] = p.target_radius[i] = max_radius * (0.6 + 0.4 * u(rng));
      p.id[i] = ids[i];
      p.motion[i] = u(rng) < 0.1 ? Motion::frozen : Motion::free;
    }
    const std::set<PairKey> expected = all_images(p, box, skin);
    long across = 0;
    for (const auto& [a, b, code] : expected) across += PeriodicBox::shift_of(static_cast<std::uint8_t>(code))[1] != 0;
    ASSERT_GT(across, 30) << "too few pairs across the sliding seam to test anything";
    NeighborPairs all;
    build_pairs_all(p, box, skin, all);
    EXPECT_EQ(listed_pairs(p, all), expected) << "offset " << offset << ": build_pairs_all";
    CellGrid grid;
    grid.setup(box, 2.0 * max_radius + skin, p.size());
    grid.bin(p.position);
    for (int threads : {1, 3}) {
      NeighborPairs cells;
      grid.build_pairs(p, box, skin, threads, cells);
      EXPECT_EQ(listed_pairs(p, cells), expected) << "offset " << offset << ", " << threads << " threads";
    }
  }
}

TEST(DemLeesEdwards, EveryOverlappingPairIsListedAtEveryStep) {
  DemEngineVariant variant = test::engine_from_toml(kShearedGas, "sheared_gas.toml", 2);
  auto& engine = std::get<DemEngine<WaltonBraun>>(variant);
  long overlapping = 0, across = 0, turns_seen = 0;
  std::int32_t turns = 0;
  for (long step = 1; step <= 3000 && !HasFailure(); ++step) {
    engine.step();
    const ParticleStore& p = engine.state().particles;
    const PeriodicBox& box = engine.state().box;
    if (box.shear_turns != turns) ++turns_seen, turns = box.shear_turns;
    std::unordered_map<std::uint64_t, std::pair<int, std::uint32_t>> listed;
    const NeighborPairs& list = engine.pairs();
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::uint32_t k = list.offsets[i]; k < list.offsets[i + 1]; ++k)
        listed[(std::uint64_t{p.id[i]} << 32) | p.id[list.partner[k]]] = {list.shift[k], k};
    for (std::size_t a = 0; a < p.size(); ++a)
      for (std::size_t b = 0; b < p.size(); ++b) {
        if (p.id[a] >= p.id[b]) continue;
        Vec3 d;
        const std::uint8_t code = nearest_image(box, p.position[a], p.position[b], d);
        if (norm(d) >= p.radius[a] + p.radius[b]) continue;
        ++overlapping;
        across += PeriodicBox::shift_of(code)[1] != 0;
        const auto it = listed.find((std::uint64_t{p.id[a]} << 32) | p.id[b]);
        if (it == listed.end()) {
          ADD_FAILURE() << "step " << step << ": overlapping pair " << p.id[a] << "-" << p.id[b] << " is not listed";
          continue;
        }
        EXPECT_EQ(it->second.first, code) << "step " << step << ": listed under another image";
        EXPECT_EQ(engine.contacts().pair_touching[it->second.second], 1) << "step " << step << ": not marked touching";
      }
  }
  // What the test claims to cover: contacts, across the seam, and turns of the offset.
  EXPECT_GT(overlapping, 1000);
  EXPECT_GT(across, 50);
  EXPECT_GE(turns_seen, 2);
  EXPECT_GT(engine.statistics().rebuilds, 20);
}

// Walton–Braun's alpha_max, the largest overlap of a contact so far, never decreases while the
// contact lasts; a history lost or given to another image restarts it at the current overlap, which
// is smaller once the contact unloads. So, step by step, every pair touching before and after keeps
// alpha_max or raises it, above all those relisted under another shift code (a seam crossing
// wrapped, a width taken off the offset). The control wipes every history at one rebuild.
TEST(DemLeesEdwards, ContactHistoriesSurviveTheSeamAndTheOffsetsTurns) {
  struct Count {
    long continuing = 0, relisted = 0, relisted_unloading = 0, decreases = 0;
  };
  constexpr int kSteps = 10000;  // ~9 widths of slide
  auto run = [](bool wipe) {
    DemEngineVariant variant = test::engine_from_toml(kShearedGas, "sheared_gas.toml", 1);
    auto& engine = std::get<DemEngine<WaltonBraun>>(variant);
    Count n;
    std::unordered_map<std::uint64_t, std::pair<double, int>> before;  // ids -> (alpha_max, code)
    bool wiped = false;
    for (int step = 1; step <= kSteps; ++step) {
      const long rebuilds = engine.statistics().rebuilds;
      engine.step();
      const ParticleStore& p = engine.state().particles;
      const NeighborPairs& list = engine.pairs();
      auto& store = const_cast<ContactStore<WaltonBraun::State>&>(engine.contacts());
      if (wipe && !wiped && step > kSteps / 2 && engine.statistics().rebuilds > rebuilds) {
        std::fill(store.pair_state.begin(), store.pair_state.end(), WaltonBraun::State{});
        engine.compute_forces(0.0);  // the forces from fresh histories (dt = 0: the springs start at zero)
        wiped = true;
      }
      std::unordered_map<std::uint64_t, std::pair<double, int>> now;
      for (std::size_t i = 0; i < p.size(); ++i)
        for (std::uint32_t k = list.offsets[i]; k < list.offsets[i + 1]; ++k) {
          if (!store.pair_touching[k]) continue;
          const std::uint64_t key = (std::uint64_t{p.id[i]} << 32) | p.id[list.partner[k]];
          const double alpha = store.pair_state[k].alpha_max;
          now[key] = {alpha, list.shift[k]};
          const auto it = before.find(key);
          if (it == before.end()) continue;
          ++n.continuing;
          const bool relisted = it->second.second != list.shift[k];
          n.relisted += relisted;
          const double overlap =
              p.radius[i] + p.radius[list.partner[k]] -
              norm(p.position[i] - (p.position[list.partner[k]] + engine.state().box.shift_table()[list.shift[k]]));
          n.relisted_unloading += relisted && overlap < alpha;
          n.decreases += alpha < it->second.first;
        }
      before.swap(now);
    }
    return n;
  };
  const Count kept = run(false);
  EXPECT_EQ(kept.decreases, 0);
  EXPECT_GT(kept.continuing, 5000);
  EXPECT_GT(kept.relisted, 20) << "too few contacts relisted under another image to test their histories";
  EXPECT_GT(kept.relisted_unloading, 8);
  EXPECT_GT(run(true).decreases, 0) << "control: forgetting the histories should show";
}
