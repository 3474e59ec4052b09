// Neighbor lists: the cell-grid search must find exactly the pairs of an all-pairs search (periodic
// axes with 2 and with many cells, open faces with particles outside the box, an MPI rank's region
// of the box), the engine's list
// must hold every overlapping pair at every step of a run with rebuilds and spatial re-sorting, and
// contact history must survive rebuilds and re-orderings (DESIGN.md; STYLE.md items 5, 6, 8).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/neighbor_list.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

using PairKey = std::tuple<std::uint32_t, std::uint32_t, int>;  // (smaller id, larger id, shift code of the larger)
// A particle and its own image form a pair (id, id, code) with code above PeriodicBox::kNoShift.

std::set<PairKey> pair_set(const ParticleStore& p, const NeighborPairs& list) {
  std::set<PairKey> out;
  EXPECT_EQ(list.offsets.size(), p.size() + 1);
  EXPECT_EQ(list.offsets.back(), list.partner.size());
  EXPECT_EQ(list.partner.size(), list.shift.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_LE(list.offsets[i], list.offsets[i + 1]);
    for (std::uint32_t k = list.offsets[i]; k < list.offsets[i + 1]; ++k) {
      const std::uint32_t j = list.partner[k];
      if (i == j)
        EXPECT_GT(list.shift[k], PeriodicBox::kNoShift)
            << "a particle's own image must be listed in the positive direction";
      else EXPECT_LT(p.id[i], p.id[j]) << "a pair must be listed under the smaller id";
      const bool inserted = out.emplace(p.id[i], p.id[j], list.shift[k]).second;
      EXPECT_TRUE(inserted) << "pair " << p.id[i] << "-" << p.id[j] << " listed twice";
    }
  }
  return out;
}

// Independent reference: every pair, every periodic image up to two box lengths away that can lie
// within the cutoff (positions lie in the box, so an image |s| lengths away is at least (|s| - 1) L
// away), no minimum-image rounding.
std::set<PairKey> brute_force(const ParticleStore& p, const PeriodicBox& box, double skin) {
  std::set<PairKey> out;
  double largest = 0.0;
  for (std::size_t a = 0; a < p.size(); ++a) largest = std::max(largest, p.target_radius[a]);
  int reach[3];
  for (int axis = 0; axis < 3; ++axis) {
    reach[axis] = 0;
    if (box.periodic[axis])
      while (reach[axis] < PeriodicBox::kMaxImage && reach[axis] * box.length(axis) < 2.0 * largest + skin)
        ++reach[axis];
  }
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = 0; b < p.size(); ++b) {
      if (p.id[a] > p.id[b]) continue;
      if (p.motion[a] != Motion::free && p.motion[b] != Motion::free) continue;  // two fixed: never computed
      const double cutoff = p.target_radius[a] + p.target_radius[b] + skin;
      for (int sz = -reach[2]; sz <= reach[2]; ++sz)
        for (int sy = -reach[1]; sy <= reach[1]; ++sy)
          for (int sx = -reach[0]; sx <= reach[0]; ++sx) {
            const std::uint8_t code = PeriodicBox::shift_code(sx, sy, sz);
            if (a == b && code <= PeriodicBox::kNoShift) continue;  // one's own image: once, positive direction
            const Vec3 shifted = p.position[b] + Vec3{sx * box.length(0), sy * box.length(1), sz * box.length(2)};
            if (norm2(p.position[a] - shifted) < cutoff * cutoff) out.emplace(p.id[a], p.id[b], code);
          }
    }
  return out;
}

struct RandomConfig {
  const char* name;
  Vec3 lo, hi;
  std::array<bool, 3> periodic;
  int particles;
  double max_radius, skin;
  double outside;  // m, how far beyond open faces particles may lie
};

ParticleStore random_particles(const RandomConfig& c, const PeriodicBox& box, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ParticleStore p;
  p.resize(c.particles);
  std::vector<std::uint32_t> ids(c.particles);
  std::iota(ids.begin(), ids.end(), 0u);
  std::shuffle(ids.begin(), ids.end(), rng);  // ids unrelated to indices, as after a re-sort
  for (int i = 0; i < c.particles; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double extra = box.periodic[axis] ? 0.0 : c.outside;
      p.position[i][axis] = c.lo[axis] - extra + u(rng) * (c.hi[axis] - c.lo[axis] + 2.0 * extra);
    }
    // A few exactly on the faces, where binning rounds.
    if (i % 37 == 0) p.position[i].x = c.lo.x;
    if (i % 41 == 0) p.position[i].y = std::nextafter(c.hi.y, c.lo.y);
    p.radius[i] = p.target_radius[i] = c.max_radius * (0.5 + 0.5 * u(rng));
    p.id[i] = ids[i];
    p.motion[i] = u(rng) < 0.15 ? Motion::frozen : Motion::free;
  }
  return p;
}

// A case run by the engine, its particles by id.
struct Snapshot {
  std::vector<Vec3> position, velocity, angular_velocity;
};

template <class Engine>
Snapshot snapshot(const Engine& engine) {
  const ParticleStore& p = engine.state().particles;
  Snapshot s;
  s.position.resize(p.size());
  s.velocity.resize(p.size());
  s.angular_velocity.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.position[p.id[i]] = engine.state().box.unwrapped(p.position[i], p.image[i]);
    s.velocity[p.id[i]] = p.velocity[i];
    s.angular_velocity[p.id[i]] = p.angular_velocity[i];
  }
  return s;
}

// Checks that every pair overlapping now (minimum image, current radii) is in the engine's list,
// under the right periodic image, and marked touching by the last force evaluation. Returns the
// number of overlapping pairs; `with_fixed` counts those with a fixed partner (a wall bump).
template <class Engine>
long check_overlaps_listed(const Engine& engine, long step, long& with_fixed) {
  const ParticleStore& p = engine.state().particles;
  const PeriodicBox& box = engine.state().box;
  const NeighborPairs& list = engine.pairs();
  auto key = [](std::uint64_t a, std::uint64_t b) { return (a << 32) | b; };
  std::unordered_map<std::uint64_t, std::pair<int, std::uint32_t>> listed;  // -> (shift, slot)
  listed.reserve(2 * list.pair_count());
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::uint32_t k = list.offsets[i]; k < list.offsets[i + 1]; ++k)
      listed[key(p.id[i], p.id[list.partner[k]])] = {list.shift[k], k};
  long overlapping = 0;
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = 0; b < p.size(); ++b) {
      if (p.id[a] >= p.id[b] || (p.motion[a] != Motion::free && p.motion[b] != Motion::free)) continue;
      Vec3 d = p.position[a] - p.position[b];
      int s[3] = {0, 0, 0};
      for (int axis = 0; axis < 3; ++axis)
        if (box.periodic[axis]) {
          s[axis] = static_cast<int>(std::nearbyint(d[axis] / box.length(axis)));
          d[axis] -= s[axis] * box.length(axis);
        }
      const double contact = p.radius[a] + p.radius[b];
      if (norm2(d) >= contact * contact) continue;
      ++overlapping;
      with_fixed += p.motion[a] != Motion::free || p.motion[b] != Motion::free;
      const auto it = listed.find(key(p.id[a], p.id[b]));
      if (it == listed.end()) {
        ADD_FAILURE() << "step " << step << ": overlapping pair " << p.id[a] << "-" << p.id[b] << " (overlap "
                      << contact - norm(d) << " m) is not in the neighbor list";
        continue;
      }
      EXPECT_EQ(it->second.first, PeriodicBox::shift_code(s[0], s[1], s[2]))
          << "step " << step << ": pair " << p.id[a] << "-" << p.id[b] << " listed under another periodic image";
      EXPECT_EQ(engine.contacts().pair_touching[it->second.second], 1)
          << "step " << step << ": pair " << p.id[a] << "-" << p.id[b] << " overlaps but is not marked touching";
    }
  return overlapping;
}

// A periodic gas of 120 spheres of two sizes (solids fraction 0.22) at T = 30 m^2/s^2, no gravity,
// friction 0.5: speeds ~10 m/s move particles half the skin every ~20 steps, so 600 steps rebuild
// the list ~30 times; with sort_every = 1 every rebuild re-sorts the particles.
const std::string kGas = R"([domain]
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
[run]
duration = 1.0
sort_every = 1
)";

// A bed falling onto a moving bumpy floor under gravity: 150 spheres on a 6 x 6 lattice of bumps,
// started on a lattice just above them with T = 4 m^2/s^2, the floor shaking at 30 Hz; 1500 steps.
const std::string kBed = R"([domain]
lo = [0.0, 0.0, 0.0]
hi = [0.018, 0.06, 0.018]
boundary = { x = "periodic", y = ["bumpy", "open"], z = "periodic" }
[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 150
[particles]
init = "lattice"
region_lo = [0.0, 0.0016, 0.0]
region_hi = [0.018, 0.06, 0.018]
initial_temperature = 4.0
seed = 9
[contact]
k1 = 1.0e6
restitution = 0.9
friction = 0.5
[walls.ylo]
spacing = 0.003
[drive]
face = "ylo"
amplitude = [0.0, 0.0005, 0.0]
frequency = [0.0, 30.0, 0.0]
ramp = 0.0
[run]
duration = 1.0
sort_every = 2
)";

}  // namespace

TEST(NeighborList, CellGridFindsExactlyTheAllPairsSet) {
  const std::vector<RandomConfig> configs = {
      // Two cells per periodic axis: the -1 and +1 neighbors are the same cell under two images.
      {"periodic, 2 cells", {0.0, 0.0, 0.0}, {0.0075, 0.0071, 0.0069}, {true, true, true}, 60, 0.0015, 0.00045, 0.0},
      {"periodic, many cells", {-0.01, 0.0, 0.02}, {0.03, 0.021, 0.05}, {true, true, true}, 600, 0.0015, 0.00045, 0.0},
      // Open y faces with particles up to 3 cells outside the box (binned into the edge cells).
      {"open y, outside", {0.0, 0.0, 0.0}, {0.015, 0.02, 0.015}, {true, false, true}, 500, 0.0015, 0.00045, 0.01},
      {"all open, outside", {0.0, 0.0, 0.0}, {0.02, 0.02, 0.02}, {false, false, false}, 400, 0.0015, 0.0003, 0.006},
      {"mixed, 2 cells on x", {0.0, 0.0, 0.0}, {0.0070, 0.03, 0.02}, {true, false, false}, 200, 0.0015, 0.0004, 0.002},
      // Narrow periodic widths, one cell across: x 0.0025 m against a cutoff of 0.00345 m holds
      // images two box lengths away; z 0.0050 m one; particles meet their own images.
      {"narrow x and z", {0.0, 0.0, 0.0}, {0.0025, 0.02, 0.0050}, {true, false, true}, 40, 0.0015, 0.00045, 0.0},
      {"narrow x, periodic y", {0.0, 0.0, 0.0}, {0.0018, 0.015, 0.02}, {true, true, false}, 60, 0.0015, 0.00045, 0.0},
  };
  for (const auto& config : configs) {
    PeriodicBox box;
    box.lo = config.lo;
    box.hi = config.hi;
    box.periodic = config.periodic;
    for (std::uint64_t seed : {1u, 2u}) {
      const ParticleStore p = random_particles(config, box, seed);
      const std::set<PairKey> expected = brute_force(p, box, config.skin);
      ASSERT_GT(expected.size(), 10u) << config.name << ": too few pairs to test anything";
      NeighborPairs all;
      build_pairs_all(p, box, config.skin, all);
      EXPECT_EQ(pair_set(p, all), expected) << config.name << ", seed " << seed << ": build_pairs_all";
      CellGrid grid;
      grid.setup(box, 2.0 * config.max_radius + config.skin, p.size());  // as the engine does
      grid.bin(p.position);
      for (int threads : {1, 3}) {
        NeighborPairs cells;
        grid.build_pairs(p, box, config.skin, threads, cells);
        EXPECT_EQ(pair_set(p, cells), expected) << config.name << ", seed " << seed << ", " << threads << " threads";
      }
    }
  }
}

// An MPI rank's grid (CellGrid::setup_region): only its slab along x and the ghost layer of width w
// on each side, the particles beyond a periodic face given at their positions in the box. The
// pairs among the particles the rank holds must be exactly the all-images search's, with the
// periodic images (shift codes) of the whole box: slabs in the middle, at either end of a periodic
// axis (ghosts from across the face), and at the ends of an open axis (particles outside the box).
TEST(NeighborList, ARanksRegionGridFindsTheWholeBoxPairsAmongItsParticles) {
  const double max_radius = 0.0015, skin = 0.00045, w = 2.0 * max_radius + skin;
  for (const bool periodic_x : {true, false}) {
    const RandomConfig config{
        "slab", {0.0, 0.0, 0.0}, {0.06, 0.02, 0.015}, {periodic_x, false, true}, 1200, max_radius, skin, 0.004};
    PeriodicBox box;
    box.lo = config.lo;
    box.hi = config.hi;
    box.periodic = config.periodic;
    const ParticleStore all = random_particles(config, box, 7);
    for (const auto& [a, b] : {std::pair{0.02, 0.035}, std::pair{0.0, 0.018}, std::pair{0.041, 0.06}}) {
      // The rank's particles: within w of [a, b] along x, through the periodic face if there is one.
      std::vector<std::uint32_t> held;
      for (std::size_t i = 0; i < all.size(); ++i) {
        const double x = all.position[i].x;
        double gap = std::max({a - x, x - b, 0.0});
        if (periodic_x)
          gap = std::min(
              {gap, std::max({a - (x - 0.06), x - 0.06 - b, 0.0}), std::max({a - (x + 0.06), x + 0.06 - b, 0.0})});
        if (!periodic_x && ((a == 0.0 && x < a) || (b == 0.06 && x > b))) gap = 0.0;  // end slabs reach on
        if (gap < w) held.push_back(static_cast<std::uint32_t>(i));
      }
      ParticleStore p = all;
      p.permute(held);
      const std::set<PairKey> expected = brute_force(p, box, skin);
      ASSERT_GT(expected.size(), 50u);
      CellGrid grid;
      grid.setup_region(box, {a - w, 0.0, 0.0}, {b + w, 0.0, 0.0}, {true, false, false}, w, p.size());
      grid.bin(p.position);
      for (int threads : {1, 2}) {
        NeighborPairs cells;
        grid.build_pairs(p, box, skin, threads, cells);
        EXPECT_EQ(pair_set(p, cells), expected)
            << "slab [" << a << ", " << b << "], periodic x " << periodic_x << ", " << threads << " threads";
      }
    }
  }
}

TEST(NeighborList, SparseHugeBoxGetsWiderCellsAndTheSamePairs) {
  // 400 particles in a 2 cm cube at one corner of a 100 m periodic box: cells one cutoff wide would
  // number 4096^3 (the per-axis cap), 275 GB of cell starts. The grid widens its cells instead
  // (at most 32768 here) and must still find exactly the brute-force pairs, across the periodic
  // faces too (the cluster straddles the box's corner).
  const RandomConfig config{
      "cluster", {-0.01, -0.01, -0.01}, {0.01, 0.01, 0.01}, {true, true, true}, 400, 0.0015, 0.00045, 0.0};
  PeriodicBox cluster;
  cluster.lo = config.lo;
  cluster.hi = config.hi;
  cluster.periodic = config.periodic;
  ParticleStore p = random_particles(config, cluster, 3);
  PeriodicBox box;
  box.lo = {0.0, 0.0, 0.0};
  box.hi = {100.0, 100.0, 100.0};
  box.periodic = {true, true, true};
  for (std::size_t i = 0; i < p.size(); ++i) box.wrap(p.position[i], p.image[i]);
  const std::set<PairKey> expected = brute_force(p, box, config.skin);
  ASSERT_GT(expected.size(), 10u);
  CellGrid grid;
  grid.setup(box, 2.0 * config.max_radius + config.skin, p.size());
  grid.bin(p.position);
  NeighborPairs cells;
  grid.build_pairs(p, box, config.skin, 1, cells);
  EXPECT_EQ(pair_set(p, cells), expected);
}

TEST(NeighborList, EveryOverlappingPairIsListedAtEveryStep) {
  for (const auto& [name, text, steps] :
       {std::tuple{"periodic gas", kGas, 600}, std::tuple{"bed on a shaken bumpy floor", kBed, 1500}}) {
    const CaseConfig c = load_case_from_string(text, std::string(name) + ".toml");
    DemEngineVariant variant = test::engine_for(c, 2);
    auto& engine = std::get<DemEngine<WaltonBraun>>(variant);
    long overlapping = 0, resorted_steps = 0, with_bumps = 0;
    for (long step = 1; step <= steps; ++step) {
      engine.step();
      overlapping += check_overlaps_listed(engine, step, with_bumps);
      const auto& id = engine.state().particles.id;
      resorted_steps += !std::is_sorted(id.begin(), id.end());
      if (HasFailure()) break;
    }
    // The test must have exercised what it claims to: contacts, rebuilds, re-orderings.
    EXPECT_GT(overlapping, 1000) << name;
    EXPECT_GT(engine.statistics().rebuilds, 10) << name;
    EXPECT_GT(resorted_steps, steps / 2) << name;
    if (c.domain.faces[2] == FaceKind::bumpy) {
      EXPECT_GT(with_bumps, 100) << name << ": the bumps were never touched";
    }
  }
}

// Contact history across rebuilds and re-sorting. Two spinning spheres in a small periodic box
// (2 x 2 x 2 cells, no gravity) collide obliquely again and again through the periodic images
// (7 collisions of ~17 steps in 20000 steps). A skin of 1e-7 m makes the engine rebuild its list at
// every step, so every contact lives through ~17 rebuilds, and with sort_every = 1 every rebuild
// re-sorts the two particles by cell: their order flips 9 times. The Walton-Braun state (alpha_max
// on unloading, the tangential force and its reversal point T*) decides the outcome of each oblique
// impact. With one pair and no gravity each force and torque is one term added to zero, so rounding
// cannot depend on the particle order: runs with sort_every = 1 and 0 must be bitwise identical,
// and any difference is lost or misplaced contact state. A control run that wipes the pair state
// once in mid-contact shows that such a loss does change the outcome.
TEST(NeighborList, ContactHistorySurvivesRebuildsAndResorting) {
  const test::ParticleFile file("two_spheres.csv",
                                "glass,0.001,0.002,0.003,0.2,2.8,0.4,0,300,-200\n"
                                "glass,0.004,0.0035,0.0045,-1.9,-1.2,2.1,150,0,400\n",
                                "species,x,y,z,vx,vy,vz,wx,wy,wz");
  const std::string text = R"([domain]
lo = [0.0, 0.0, 0.0]
hi = [0.0065, 0.0065, 0.0065]
boundary = { x = "periodic", y = "periodic", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
[particles]
init = "file"
file = ")" + file.path() + R"("
[contact]
k1 = 1.0e6
restitution = 0.9
friction = 0.5
[run]
duration = 1.0
skin = 1e-7
)";
  struct Record {
    std::vector<WaltonBraun::State> states;  // per step in contact
    std::vector<Snapshot> samples;
    long rebuilds = 0, collisions = 0, flips = 0, contact_steps = 0;
  };
  auto run = [&](int sort_every, long wipe_at_contact_step) {
    Record rec;
    DemEngineVariant variant =
        test::engine_from_toml(text, "two_spheres.toml", 1, {"run.sort_every=" + std::to_string(sort_every)});
    auto& engine = std::get<DemEngine<WaltonBraun>>(variant);
    bool was_touching = false;
    std::uint32_t first = engine.state().particles.id[0];
    for (long step = 1; step <= 20000; ++step) {
      engine.step();
      const auto& contacts = engine.contacts();
      const bool touching = engine.pairs().pair_count() == 1 && contacts.pair_touching[0];
      if (touching) {
        ++rec.contact_steps;
        if (rec.contact_steps == wipe_at_contact_step)  // control only: forget the contact's history
          const_cast<ContactStore<WaltonBraun::State>&>(contacts).pair_state[0] = WaltonBraun::State{};
        rec.states.push_back(contacts.pair_state[0]);
      }
      rec.collisions += touching && !was_touching;
      was_touching = touching;
      const std::uint32_t now_first = engine.state().particles.id[0];
      rec.flips += now_first != first;
      first = now_first;
      if (step % 250 == 0) rec.samples.push_back(snapshot(engine));
    }
    rec.rebuilds = engine.statistics().rebuilds;
    return rec;
  };
  const Record sorted = run(1, -1), plain = run(0, -1);

  // The scenario is what it claims to be.
  EXPECT_GE(plain.collisions, 5);
  EXPECT_GE(plain.contact_steps, 5 * 10);
  EXPECT_GE(sorted.flips, 5) << "re-sorting rarely changed the order: the test no longer covers re-ordering";
  EXPECT_EQ(plain.flips, 0);
  EXPECT_EQ(sorted.rebuilds, 20001);  // the first build, then every step
  double largest_tangential = 0.0;
  for (const auto& state : plain.states)
    largest_tangential = std::max(largest_tangential, norm(state.tangential_force));
  EXPECT_GT(largest_tangential, 0.1) << "no tangential force to carry";

  // Bitwise identical contact histories and trajectories.
  ASSERT_EQ(sorted.states.size(), plain.states.size());
  for (std::size_t k = 0; k < plain.states.size(); ++k) {
    const auto &a = sorted.states[k], &b = plain.states[k];
    if (!(a.tangential_force == b.tangential_force) || a.alpha_max != b.alpha_max || a.t_star != b.t_star ||
        a.unloading != b.unloading) {
      ADD_FAILURE() << "contact state differs first at contact step " << k + 1 << ": alpha_max " << a.alpha_max
                    << " vs " << b.alpha_max << ", tangential x " << a.tangential_force.x << " vs "
                    << b.tangential_force.x;
      break;
    }
  }
  ASSERT_EQ(sorted.samples.size(), plain.samples.size());
  for (std::size_t k = 0; k < plain.samples.size(); ++k)
    for (int id = 0; id < 2; ++id) {
      EXPECT_EQ(sorted.samples[k].position[id], plain.samples[k].position[id]) << "sample " << k << " id " << id;
      EXPECT_EQ(sorted.samples[k].velocity[id], plain.samples[k].velocity[id]) << "sample " << k << " id " << id;
      EXPECT_EQ(sorted.samples[k].angular_velocity[id], plain.samples[k].angular_velocity[id])
          << "sample " << k << " id " << id;
    }

  // Control: forgetting the history once, 8 steps into the first contact, changes the end state.
  const Record wiped = run(0, 8);
  const Vec3 dv = wiped.samples.back().velocity[0] - plain.samples.back().velocity[0];
  EXPECT_GT(norm(dv), 1e-3) << "the comparison above could not see a lost contact history";
}

// Many particles: re-sorting changes the order in which pair forces are summed, so runs with and
// without re-sorting differ by round-off (1e-16 relative) that the collisions amplify; over 1000
// steps of the gas (several collisions per particle, dozens of rebuilds and re-sorts) the measured
// difference is ~1e-13 m/s. A lost or misplaced contact history changes contact forces at once: the
// control run, which forgets every pair's and wall contact's history once, differs by ~0.1..1 m/s.
// The bound 1e-8 m/s lies more than four decades from each. Run on the periodic gas and on the same
// gas between two flat y walls (wall contact histories are re-ordered with the particles too).
TEST(NeighborList, ResortingDoesNotChangeAManyParticleRun) {
  auto run = [](const std::vector<std::string>& overrides, int sort_every, int wipe_at_step) {
    std::vector<std::string> all = overrides;
    all.push_back("run.sort_every=" + std::to_string(sort_every));
    DemEngineVariant variant = test::engine_from_toml(kGas, "gas.toml", 1, all);
    auto& engine = std::get<DemEngine<WaltonBraun>>(variant);
    for (int step = 1; step <= 1000; ++step) {
      engine.step();
      if (step == wipe_at_step) {  // control only: forget every contact's history
        auto& store = const_cast<ContactStore<WaltonBraun::State>&>(engine.contacts());
        std::fill(store.pair_state.begin(), store.pair_state.end(), WaltonBraun::State{});
        for (auto& wall : store.walls) std::fill(wall.state.begin(), wall.state.end(), WaltonBraun::State{});
      }
    }
    return snapshot(engine);
  };
  auto largest_difference = [](const Snapshot& a, const Snapshot& b) {
    double largest = 0.0;
    for (std::size_t id = 0; id < a.velocity.size(); ++id) {
      largest = std::max(largest, norm(a.velocity[id] - b.velocity[id]));
      largest = std::max(largest, 1e-3 * norm(a.angular_velocity[id] - b.angular_velocity[id]));  // r w ~ 1e-3 w
    }
    return largest;
  };
  const std::vector<std::vector<std::string>> variants = {{}, {"domain.boundary.y=\"wall\""}};
  for (const auto& overrides : variants) {
    const std::string name = overrides.empty() ? "periodic gas" : "gas between y walls";
    const Snapshot sorted = run(overrides, 1, -1), plain = run(overrides, 0, -1), wiped = run(overrides, 0, 500);
    const double resorting = largest_difference(sorted, plain), forgetting = largest_difference(wiped, plain);
    EXPECT_LT(resorting, 1e-8) << name << ": velocities of the sorted and unsorted runs differ by up to " << resorting
                               << " m/s";
    EXPECT_GT(forgetting, 1e-8) << name << ": control: forgetting the contact history changed velocities by only "
                                << forgetting;
  }
}
