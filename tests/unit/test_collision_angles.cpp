// The collision-angle histogram (observe/collision_angles.hpp, Campbell 1982 section 3.4.2): the
// folding of a line of centres into [0, 180) degrees, the normalisation, and the flat distribution
// 1/pi of an elastic gas in equilibrium, in 2D and (projected on x-y) in 3D.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/edmd/edmd_engine.hpp"
#include "grainflow/observe/collision_angles.hpp"

#include "elastic_gas_case.hpp"

using namespace grainflow;
using observe::CollisionAngles;

namespace {

#ifdef NDEBUG
constexpr double kRunScale = 1.0;
#else
constexpr double kRunScale = 0.1;
#endif

class AngleRecorder : public engine_api::CollisionObserver {
 public:
  void on_pair(const engine_api::PairCollision& c) override { angles.add(c.normal); }
  CollisionAngles angles;
};

// An elastic smooth gas of unit particles at packing fraction 0.3 in a periodic box, T = 1.
std::string gas(int dim, int n) { return test::elastic_gas_case({dim, n, 0.3}); }

// Every bin's count within 4.5 binomial standard deviations of N/50 (all 50 pass by chance with
// probability 1 - 3e-4 for independent collisions), and chi^2 over the 49 degrees of freedom below
// its mean + 5 standard deviations (49 + 5 sqrt(98)).
template <int Dim>
void check_flat(int n, double duration) {
  edmd::EdmdEngine<Dim> e(edmd::build_edmd_state(load_case_from_string(gas(Dim, n), "angles.toml")));
  e.advance_to(5.0);  // melt the lattice
  AngleRecorder rec;
  const long long before = e.counters().collisions;
  e.set_observer(&rec);
  e.advance_to(5.0 + duration);
  const CollisionAngles& a = rec.angles;
  ASSERT_EQ(a.total() + a.skipped(), e.counters().collisions - before);  // every collision reported once
  ASSERT_GT(a.total(), 20000 * kRunScale);
  const double p = 1.0 / a.bins(), expected = a.total() * p, sigma = std::sqrt(a.total() * p * (1.0 - p));
  double chi2 = 0.0, integral = 0.0;
  for (int k = 0; k < a.bins(); ++k) {
    EXPECT_NEAR(a.count(k), expected, 4.5 * sigma) << "bin " << k;
    chi2 += (a.count(k) - expected) * (a.count(k) - expected) / expected;
    integral += a.density(k) * a.bin_width();
  }
  EXPECT_LT(chi2, 49.0 + 5.0 * std::sqrt(98.0));
  EXPECT_NEAR(integral, 1.0, 1e-12);
  EXPECT_NEAR(a.density(a.bins() / 2), 1.0 / M_PI, 4.5 * sigma / (a.total() * a.bin_width()));
}

}  // namespace

TEST(CollisionAngles, FoldsTheLineOfCentresIntoHalfATurn) {
  EXPECT_DOUBLE_EQ(CollisionAngles::angle_of({1.0, 1.0, 0.0}), M_PI / 4.0);
  EXPECT_DOUBLE_EQ(CollisionAngles::angle_of({-1.0, -1.0, 0.0}), M_PI / 4.0);  // the same collision seen from j
  EXPECT_DOUBLE_EQ(CollisionAngles::angle_of({-1.0, 1.0, 0.0}), 3.0 * M_PI / 4.0);
  EXPECT_DOUBLE_EQ(CollisionAngles::angle_of({1.0, -1.0, 5.0}), 3.0 * M_PI / 4.0);  // z is projected out
  EXPECT_EQ(CollisionAngles::angle_of({1.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(CollisionAngles::angle_of({-1.0, 0.0, 0.0}), 0.0);  // 180 degrees is 0
  EXPECT_EQ(CollisionAngles::angle_of({-1.0, -0.0, 0.0}), 0.0);
  CollisionAngles a;
  a.add({-1.0, 1e-3, 0.0});  // just below 180 degrees: the last bin
  a.add({-0.01, 1.0, 0.0});  // just above 90 degrees: bin 25 of 50
  a.add({0.0, 0.0, 1.0});    // along z: no angle
  EXPECT_EQ(a.count(49), 1);
  EXPECT_EQ(a.count(25), 1);
  EXPECT_EQ(a.total(), 2);
  EXPECT_EQ(a.skipped(), 1);
  EXPECT_DOUBLE_EQ(a.density(25), 1.0 / (2.0 * a.bin_width()));
  EXPECT_DOUBLE_EQ(a.centre(0) * 180.0 / M_PI, 1.8);
}

TEST(CollisionAngles, ElasticGasCollidesIsotropically2D) { check_flat<2>(20, 400.0 * kRunScale); }
TEST(CollisionAngles, ElasticGasCollidesIsotropically3D) { check_flat<3>(8, 100.0 * kRunScale); }
