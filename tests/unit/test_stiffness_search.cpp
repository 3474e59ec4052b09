// The search of `grainflow calibrate` (app/stiffness_search.hpp) on synthetic overlap curves: the
// linear-spring impact alpha_max / d = v sqrt(m / K1) / d, whose threshold K_needed is known. Up from
// a soft start and down from a stiff one, the answer K passes and K / factor fails (the bracket);
// the trials run are exactly the grid points start * factor^n; max_trials, the rounding of trial
// values, non-monotone and NaN measurements, and bad settings.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "grainflow/run/stiffness_search.hpp"

using namespace grainflow::run;

namespace {

// A sphere of mass m hitting a floor at v: alpha_max / d = v sqrt(m / K1) / d; 1% of d at K_needed.
constexpr double kMass = 3.52e-5, kSpeed = 1.0, kDiameter = 0.003;
const double kNeeded = kMass * std::pow(kSpeed / (0.01 * kDiameter), 2);

double impact_overlap(double k1) { return kSpeed * std::sqrt(kMass / k1) / kDiameter; }

StiffnessSearchSettings settings(double start, double factor = 1.25, int max_trials = 20) {
  return {start, factor, 0.01, max_trials};
}

void expect_bracket(const StiffnessSearchResult& r, double factor) {
  ASSERT_TRUE(r.chosen.has_value());
  ASSERT_TRUE(r.bracketed);
  const double k = r.trials[*r.chosen].k1;
  EXPECT_GE(k, kNeeded);
  EXPECT_LT(k, factor * kNeeded * (1 + 1e-5));
  EXPECT_TRUE(r.trials[*r.chosen].passed);
  // The failing neighbour K / factor was run.
  bool below_failed = false;
  for (const auto& t : r.trials)
    if (std::fabs(t.k1 / (k / factor) - 1.0) < 1e-5 && !t.passed) below_failed = true;
  EXPECT_TRUE(below_failed);
  // The answer is the smallest passing K1 run.
  for (const auto& t : r.trials) {
    if (t.passed) {
      EXPECT_GE(t.k1, k);
    }
  }
}

}  // namespace

TEST(StiffnessSearch, GoesUpFromASoftStartLikeLan) {
  const double start = kNeeded / 10.0;
  std::vector<double> asked;
  const auto r = search_stiffness(settings(start), [&](double k1) {
    asked.push_back(k1);
    return impact_overlap(k1);
  });
  expect_bracket(r, 1.25);
  EXPECT_FALSE(r.descended);
  EXPECT_EQ(r.trials.size(), 12u);  // 1.25^11 = 11.6 > 10 > 1.25^10 = 9.3
  EXPECT_EQ(r.trials.size(), asked.size());
  for (std::size_t n = 0; n < asked.size(); ++n) EXPECT_DOUBLE_EQ(asked[n], trial_stiffness(start, 1.25, int(n)));
}

// Lan's start K1_H / 100 may lie a factor 100 below: 22 trials of 1.25 to get there.
TEST(StiffnessSearch, StopsAfterMaxTrialsWithoutAnAnswer) {
  const auto r = search_stiffness(settings(kNeeded / 100.0, 1.25, 20), impact_overlap);
  EXPECT_FALSE(r.chosen.has_value());
  EXPECT_FALSE(r.bracketed);
  EXPECT_EQ(r.trials.size(), 20u);
  for (const auto& t : r.trials) EXPECT_FALSE(t.passed);
}

TEST(StiffnessSearch, ReachesTheAnswerWithEnoughTrials) {
  const auto r = search_stiffness(settings(kNeeded / 100.0, 1.25, 30), impact_overlap);
  expect_bracket(r, 1.25);
  EXPECT_EQ(r.trials.size(), 22u);  // 1.25^21 = 108 > 100 > 1.25^20 = 86.7
  EXPECT_EQ(*r.chosen, 21u);
}

TEST(StiffnessSearch, StepsDownFromAStiffStartToTheSmallestPassingK1) {
  const double start = kNeeded * 7.3;
  const auto r = search_stiffness(settings(start, 1.5), impact_overlap);
  expect_bracket(r, 1.5);
  EXPECT_TRUE(r.descended);
  EXPECT_EQ(*r.chosen, r.trials.size() - 2);  // the last trial is the failing one
  EXPECT_FALSE(r.trials.back().passed);
  for (std::size_t n = 0; n < r.trials.size(); ++n)
    EXPECT_DOUBLE_EQ(r.trials[n].k1, trial_stiffness(start, 1.5, -int(n)));
}

TEST(StiffnessSearch, TheAnswerDoesNotDependOnTheDirection) {
  // Same grid (start * 1.25^n), reached from below and from above.
  const double start = kNeeded * 0.3;
  const auto up = search_stiffness(settings(start), impact_overlap);
  const auto down = search_stiffness(settings(trial_stiffness(start, 1.25, 9)), impact_overlap);
  ASSERT_TRUE(up.chosen && down.chosen);
  EXPECT_NEAR(up.trials[*up.chosen].k1, down.trials[*down.chosen].k1, 1e-5 * kNeeded);
}

TEST(StiffnessSearch, AStartThatNeverFailsDownwardsIsNotBracketed) {
  // No impacts: the overlap is 0 whatever K1 is.
  const auto r = search_stiffness(settings(1e5, 1.25, 5), [](double) { return 0.0; });
  ASSERT_TRUE(r.chosen.has_value());
  EXPECT_TRUE(r.descended);
  EXPECT_FALSE(r.bracketed);
  EXPECT_EQ(r.trials.size(), 5u);
  EXPECT_EQ(*r.chosen, 4u);  // the smallest K1 tried
}

TEST(StiffnessSearch, OneTrialAllowed) {
  const auto pass = search_stiffness(settings(kNeeded * 2, 1.25, 1), impact_overlap);
  ASSERT_TRUE(pass.chosen.has_value());
  EXPECT_EQ(*pass.chosen, 0u);
  EXPECT_FALSE(pass.bracketed);
  const auto fail = search_stiffness(settings(kNeeded / 2, 1.25, 1), impact_overlap);
  EXPECT_FALSE(fail.chosen.has_value());
}

TEST(StiffnessSearch, TheFirstCrossingWinsOnANonMonotoneCurve) {
  // Passes at 1.25^2 start, fails again at 1.25^3 (a chaotic bed need not be monotone): the search
  // stops at the first pass going up.
  const double start = 1000.0;
  const auto r = search_stiffness(settings(start), [&](double k1) {
    const double n = std::round(std::log(k1 / start) / std::log(1.25));
    return n == 2.0 || n >= 5.0 ? 0.005 : 0.02;
  });
  ASSERT_TRUE(r.chosen.has_value());
  EXPECT_EQ(r.trials.size(), 3u);
  EXPECT_DOUBLE_EQ(r.trials[*r.chosen].k1, trial_stiffness(start, 1.25, 2));
}

TEST(StiffnessSearch, ANaNMeasurementFails) {
  const auto r = search_stiffness(settings(1000.0, 2.0, 3), [](double k1) { return k1 < 3000.0 ? NAN : 0.001; });
  ASSERT_TRUE(r.chosen.has_value());
  EXPECT_DOUBLE_EQ(r.trials[*r.chosen].k1, 4000.0);
  EXPECT_FALSE(r.trials[0].passed);
}

TEST(StiffnessSearch, AnOverlapExactlyAtTheLimitPasses) {
  const auto r = search_stiffness(settings(1000.0, 2.0, 3), [](double k1) { return k1 < 3000.0 ? 0.0100001 : 0.01; });
  ASSERT_TRUE(r.chosen.has_value());
  EXPECT_DOUBLE_EQ(r.trials[*r.chosen].k1, 4000.0);
}

TEST(StiffnessSearch, TrialValuesAreRoundedToSixDigits) {
  EXPECT_DOUBLE_EQ(trial_stiffness(1e5, 1.25, 0), 1e5);
  EXPECT_DOUBLE_EQ(trial_stiffness(1e5, 1.25, 5), 305176.0);  // 305175.78125
  EXPECT_DOUBLE_EQ(trial_stiffness(123456789.0, 1.25, 0), 123457000.0);
  EXPECT_DOUBLE_EQ(trial_stiffness(1e5, 1.25, -1), 80000.0);
  EXPECT_DOUBLE_EQ(trial_stiffness(2.7e8 / 100, 1.1, 1), 2.97e6);
}

TEST(StiffnessSearch, RejectsBadSettings) {
  const auto f = [](double) { return 0.0; };
  EXPECT_THROW(search_stiffness(settings(0.0), f), std::invalid_argument);
  EXPECT_THROW(search_stiffness(settings(-1.0), f), std::invalid_argument);
  EXPECT_THROW(search_stiffness(settings(1e5, 1.0), f), std::invalid_argument);
  EXPECT_THROW(search_stiffness(settings(1e5, 0.5), f), std::invalid_argument);
  EXPECT_THROW(search_stiffness(settings(1e5, 1.25, 0), f), std::invalid_argument);
  EXPECT_THROW(search_stiffness({1e5, 1.25, 0.0, 20}, f), std::invalid_argument);
}
