// Trajectory sampling (src/grainflow/observe/trajectory_sampler.hpp; Lan 1994 sections 3.2-3.3):
// each sample is the time average over its window t_s of the velocity and the unwrapped position,
// with a step cut by a window end shared by overlap (t_s = 7.5 steps at n = 15). Checked against
// averages computed by hand for piecewise-constant states, which are exact up to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grainflow/observe/trajectory_sampler.hpp"

using namespace grainflow;
using namespace grainflow::observe;

namespace {

struct Sample {
  double time;
  std::vector<double> velocity, position;
};

ParticleStore two_particles() {
  ParticleStore p;
  p.resize(2);
  for (std::size_t i = 0; i < 2; ++i) {
    p.id[i] = static_cast<std::uint32_t>(i);
    p.motion[i] = Motion::free;
    p.radius[i] = p.target_radius[i] = 0.5;
  }
  return p;
}

PeriodicBox unit_periodic_box() {
  PeriodicBox box;
  box.lo = {0.0, 0.0, 0.0};
  box.hi = {1.0, 1.0, 1.0};
  box.periodic = {true, true, true};
  return box;
}

}  // namespace

// Step k (k = 1, 2, ...) holds particle 1 at velocity (k, 0, 0): with windows of 1.5 steps the
// first window covers step 1 and half of step 2, so its mean is (1 + 0.5 * 2) / 1.5 = 4/3, the
// second the other half of step 2 and step 3: (0.5 * 2 + 3) / 1.5 = 8/3; and so on.
TEST(TrajectorySampler, WindowsCuttingStepsWeighThemByOverlap) {
  std::vector<Sample> samples;
  const double dt = 0.1;
  TrajectorySampler sampler({1}, 0.0, 1.5 * dt, 4, [&](double t, const auto& v, const auto& x) {
    samples.push_back({t, v, x});
  });
  ParticleStore p = two_particles();
  const PeriodicBox box = unit_periodic_box();
  for (int k = 1; k <= 7 && !sampler.done(); ++k) {
    p.velocity[1] = {double(k), 0.0, 0.0};
    p.velocity[0] = {100.0, 100.0, 100.0};  // not followed: must not leak into the samples
    sampler.observe(p, box, (k - 1) * dt, k * dt);
  }
  ASSERT_EQ(samples.size(), 4u);
  // Window j covers steps with weights: exact expectations from the overlap rule.
  const double expected[4] = {(1.0 + 0.5 * 2.0) / 1.5, (0.5 * 2.0 + 3.0) / 1.5, (4.0 + 0.5 * 5.0) / 1.5,
                              (0.5 * 5.0 + 6.0) / 1.5};
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(samples[j].velocity[0], expected[j], 1e-12) << "window " << j;
    EXPECT_EQ(samples[j].velocity[1], 0.0);
    EXPECT_NEAR(samples[j].time, (j + 0.5) * 1.5 * dt, 1e-15);
  }
  EXPECT_TRUE(sampler.done());
}

// Positions are unwrapped with the image counters: a particle that crossed the periodic face once
// (image +1) at x = 0.2 is at 1.2; samples before the start time are not taken.
TEST(TrajectorySampler, PositionsAreUnwrappedAndStartIsRespected) {
  std::vector<Sample> samples;
  TrajectorySampler sampler({0, 1}, 1.0, 0.5, 2, [&](double t, const auto& v, const auto& x) {
    samples.push_back({t, v, x});
  });
  ParticleStore p = two_particles();
  const PeriodicBox box = unit_periodic_box();
  p.position[0] = {0.2, 0.3, 0.4};
  p.image[0] = {1, 0, -2};
  p.position[1] = {0.5, 0.5, 0.5};
  for (int k = 1; k <= 4; ++k) sampler.observe(p, box, (k - 1) * 0.5, k * 0.5);  // steps of 0.5 s
  ASSERT_EQ(samples.size(), 2u);  // the step ending at 0.5 and 1.0 come before start = 1.0
  EXPECT_NEAR(samples[0].time, 1.25, 1e-15);
  EXPECT_NEAR(samples[0].position[0], 1.2, 1e-15);
  EXPECT_NEAR(samples[0].position[1], 0.3, 1e-15);
  EXPECT_NEAR(samples[0].position[2], -1.6, 1e-15);
  EXPECT_NEAR(samples[0].position[3], 0.5, 1e-15);
}

// Lan's windows: t_s = 7.5 steps with a step of 6.3135e-5 s (Table 4.4), a constant velocity: every
// sample equals it to round-off, and 2000 samples take exactly 15000 steps (each window closes at
// the step it should, even though k * dt is not exact in floating point).
TEST(TrajectorySampler, LanWindowsOfSevenAndAHalfStepsCloseOnTime) {
  const double dt = 6.3135e-5;
  long taken = 0;
  double worst = 0.0;
  TrajectorySampler sampler({0}, 0.0, 7.5 * dt, 2000, [&](double, const auto& v, const auto&) {
    ++taken;
    worst = std::max(worst, std::fabs(v[1] / 0.25 - 1.0));
  });
  ParticleStore p = two_particles();
  p.velocity[0] = {0.0, 0.25, 0.0};
  const PeriodicBox box = unit_periodic_box();
  long steps = 0;
  while (!sampler.done()) {
    ++steps;
    sampler.observe(p, box, (steps - 1) * dt, steps * dt);
  }
  EXPECT_EQ(taken, 2000);
  EXPECT_EQ(steps, 15000);
  EXPECT_LT(worst, 1e-9);  // weights sum to the window up to the 1e-9 closing tolerance
}
