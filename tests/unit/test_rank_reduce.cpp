// The observers of an MPI run (observe/rank_reduce.hpp): each rank measures its own particles and
// the sums are added over the ranks. Here two "ranks" are two threads in this process, each holding
// one half of a bed (split at x = 0.5 L) plus ghost copies of the other half's particles near the
// cut, and adding their sums through a barrier, as MPI_Allreduce would. Every observer must give
// what one rank gives over the whole bed: the ghosts must not count, and every sum must be added.
// The halves add their sums in another association than one loop does, which changes a sum of n
// terms by ~n 1e-16 of its magnitude: the bound 1e-12 (relative) lies far above that, and far
// below a particle counted twice or lost (>= 1e-3 of any of these sums for a bed of 300).
#include <gtest/gtest.h>

#include <barrier>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include "grainflow/observe/bed_surface.hpp"
#include "grainflow/observe/global_sample.hpp"
#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/observe/trajectory_sampler.hpp"
#include "grainflow/observe/velocity_field.hpp"
#include "grainflow/observe/zone_profile.hpp"

using namespace grainflow;
using namespace grainflow::observe;

namespace {

constexpr double kD = 0.003, kL = 0.03;  // sphere diameter and box side, m

// Two threads adding their values element by element, the way MPI_Allreduce does for two ranks.
class TwoRanks {
 public:
  RankReduce reduce(int rank) {
    RankReduce r;
    r.sum_in_place = [this, rank](double* values, std::size_t count) {
      slot_[rank].assign(values, values + count);
      sync_.arrive_and_wait();
      for (std::size_t k = 0; k < count; ++k) values[k] = slot_[0][k] + slot_[1][k];
      sync_.arrive_and_wait();  // both read before either writes again
    };
    r.max_over_ranks = [this, rank](double local) {
      slot_[rank].assign(1, local);
      sync_.arrive_and_wait();
      const double m = std::max(slot_[0][0], slot_[1][0]);
      sync_.arrive_and_wait();
      return m;
    };
    return r;
  }
  // Runs `work(rank, reduce)` on both ranks at once.
  template <class Work>
  void run(Work&& work) {
    std::thread other([&] { work(1, reduce(1)); });
    work(0, reduce(0));
    other.join();
  }

 private:
  std::vector<double> slot_[2];
  std::barrier<> sync_{2};
};

// A bed of 300 spheres of two sizes in the lower half of the box, moving at random.
ParticleStore bed() {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ParticleStore p;
  p.resize(300);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.id[i] = static_cast<std::uint32_t>(i);
    p.motion[i] = Motion::free;
    p.radius[i] = p.target_radius[i] = (i % 3 == 0 ? 0.6 : 0.5) * kD;
    p.mass[i] = 2500.0 * 4.0 / 3.0 * M_PI * std::pow(p.radius[i], 3);
    p.inv_mass[i] = 1.0 / p.mass[i];
    p.inv_inertia[i] = 1.0 / (0.4 * p.mass[i] * p.radius[i] * p.radius[i]);
    p.position[i] = {kL * u(rng), 0.5 * kL * u(rng) * u(rng), kL * u(rng)};  // denser low down
    p.velocity[i] = {u(rng) - 0.5, u(rng) - 0.3, u(rng) - 0.5};
    p.angular_velocity[i] = {100.0 * u(rng), 0.0, -50.0 * u(rng)};
  }
  p.ghost.assign(p.size(), 0);
  return p;
}

// Rank `rank`'s store: the particles on its side of x = L / 2, then ghost copies of those on the
// other side within two diameters of the cut.
ParticleStore half(const ParticleStore& all, int rank) {
  ParticleStore p;
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < all.size(); ++i) {
      const bool mine = (all.position[i].x < 0.5 * kL) == (rank == 0);
      const bool near_cut = std::fabs(all.position[i].x - 0.5 * kL) < 2.0 * kD;
      if (pass == 0 ? !mine : (mine || !near_cut)) continue;
      ParticleStore::Record r = all.record(i);
      r.ghost = pass == 1;
      p.push_back(r);
    }
  return p;
}

void expect_close(double a, double b, const char* what) {
  EXPECT_NEAR(a, b, 1e-12 * std::max(std::fabs(a), std::fabs(b)) + 1e-300) << what;
}

TEST(RankReduce, HalvesWithGhostsGiveTheWholeBedsGlobalSample) {
  const ParticleStore all = bed();
  const GlobalSample whole = sample_global(all, 1, 3);
  TwoRanks ranks;
  GlobalSample parts[2];
  ranks.run([&](int rank, RankReduce reduce) { parts[rank] = sample_global(half(all, rank), 1, 3, reduce); });
  for (const GlobalSample& g : parts) {
    expect_close(g.mass, whole.mass, "mass");
    expect_close(g.kinetic_energy, whole.kinetic_energy, "kinetic energy");
    expect_close(g.rotational_energy, whole.rotational_energy, "rotational energy");
    expect_close(g.granular_temperature, whole.granular_temperature, "granular temperature");
    expect_close(g.mass_center_height, whole.mass_center_height, "mass centre");
  }
}

TEST(RankReduce, HalvesWithGhostsGiveTheWholeBedsSurface) {
  const ParticleStore all = bed();
  const BedSurfaceThresholds thresholds;
  const BedSurface whole = measure_bed_surface(all, 3, 1, 0.0, kL * kL, kD, thresholds);
  ASSERT_GT(whole.height, kD);
  TwoRanks ranks;
  BedSurface parts[2];
  ranks.run([&](int rank, RankReduce reduce) {
    parts[rank] = measure_bed_surface(half(all, rank), 3, 1, 0.0, kL * kL, kD, thresholds, reduce);
  });
  for (const BedSurface& b : parts) {
    expect_close(b.height, whole.height, "height");
    expect_close(b.bulk_solids_fraction, whole.bulk_solids_fraction, "bulk solids fraction");
    EXPECT_EQ(b.ballistic, whole.ballistic);
  }
}

TEST(RankReduce, HalvesWithGhostsGiveTheWholeBedsZoneProfiles) {
  const ParticleStore all = bed();
  ZoneProfile whole(1, 0.0, kL, kD, kL * kL);
  whole.sample(all);
  const double whole_temperature = whole.instantaneous_temperature(all);
  TwoRanks ranks;
  std::vector<ZoneAverages> parts[2];
  double temperature[2];
  ranks.run([&](int rank, RankReduce reduce) {
    ZoneProfile profile(1, 0.0, kL, kD, kL * kL);
    profile.set_reduce(reduce);
    const ParticleStore mine = half(all, rank);
    profile.sample(mine);
    temperature[rank] = profile.instantaneous_temperature(mine);
    parts[rank] = profile.averages();
  });
  const auto expected = whole.averages();
  for (int rank = 0; rank < 2; ++rank) {
    expect_close(temperature[rank], whole_temperature, "cell temperature");
    ASSERT_EQ(parts[rank].size(), expected.size());
    for (std::size_t z = 0; z < expected.size(); ++z) {
      expect_close(parts[rank][z].solids_fraction, expected[z].solids_fraction, "solids fraction");
      expect_close(parts[rank][z].mean_velocity.y, expected[z].mean_velocity.y, "mean velocity");
      expect_close(parts[rank][z].temperature_lan.x, expected[z].temperature_lan.x, "temperature");
    }
  }
}

TEST(RankReduce, AParticleChangingRanksMidWindowKeepsItsWholeTrajectoryAverage) {
  ParticleStore all = bed();
  PeriodicBox box;
  box.hi = {kL, kL, kL};
  box.periodic = {true, false, true};
  const std::vector<std::uint32_t> ids = {3, 150, 299};
  // Four steps of dt in one window; particle 150 is on rank 0 for two steps, then on rank 1.
  const double dt = 1e-4;
  auto step_state = [&](int k) {
    ParticleStore p = all;
    for (std::size_t i = 0; i < p.size(); ++i) p.position[i] += (k * dt) * p.velocity[i];
    p.position[150].x = k < 2 ? 0.4 * kL : 0.6 * kL;
    return p;
  };
  std::vector<double> whole_v, whole_x;
  TrajectorySampler whole(ids, 0.0, 4 * dt, 1, [&](double, const auto& v, const auto& x) { whole_v = v, whole_x = x; });
  for (int k = 1; k <= 4; ++k) whole.observe(step_state(k), box, (k - 1) * dt, k * dt);
  TwoRanks ranks;
  std::vector<double> part_v[2], part_x[2];
  ranks.run([&](int rank, RankReduce reduce) {
    TrajectorySampler sampler(ids, 0.0, 4 * dt, 1, [&](double, const auto& v, const auto& x) {
      part_v[rank] = v;
      part_x[rank] = x;
    });
    sampler.set_reduce(reduce);
    for (int k = 1; k <= 4; ++k) sampler.observe(half(step_state(k), rank), box, (k - 1) * dt, k * dt);
  });
  for (int rank = 0; rank < 2; ++rank) {
    ASSERT_EQ(part_v[rank].size(), whole_v.size());
    for (std::size_t k = 0; k < whole_v.size(); ++k) {
      expect_close(part_v[rank][k], whole_v[k], "window velocity");
      expect_close(part_x[rank][k], whole_x[k], "window position");
    }
  }
}

TEST(RankReduce, VelocityFieldCellsAddOverTheRanks) {
  const ParticleStore all = bed();
  VelocityField whole(0, 1, 0.0, kL, 0.0, kL, 2 * kD, 2);
  whole.sample(all, 1);
  TwoRanks ranks;
  std::vector<FieldCell> parts[2];
  ranks.run([&](int rank, RankReduce reduce) {
    VelocityField field(0, 1, 0.0, kL, 0.0, kL, 2 * kD, 2);
    field.sample(half(all, rank), 1);
    field.sum_over_ranks(reduce);
    parts[rank] = field.cells(1);
  });
  const auto expected = whole.cells(1);
  long visits = 0;
  for (int rank = 0; rank < 2; ++rank) {
    ASSERT_EQ(parts[rank].size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      EXPECT_EQ(parts[rank][k].visits, expected[k].visits);
      expect_close(parts[rank][k].velocity_vertical, expected[k].velocity_vertical, "cell velocity");
      if (rank == 0) visits += expected[k].visits;
    }
  }
  EXPECT_EQ(visits, 300);  // every sphere of the bed lies in the field
}

}  // namespace
