// The stall detector: a window of 100 N + 1000 events must move time by more than 1e-9 of its value.
#include <gtest/gtest.h>

#include "grainflow/edmd/stall_detector.hpp"

using grainflow::edmd::StallDetector;

TEST(StallDetector, EventsAtOneInstantStallAfterOneWindow) {
  StallDetector d;
  d.start(5.0);
  const long long window = StallDetector::window(10);
  ASSERT_EQ(window, 2000);
  for (long long k = 1; k < window; ++k) ASSERT_FALSE(d.stalled(10, 5.0)) << "event " << k;
  EXPECT_TRUE(d.stalled(10, 5.0));
  EXPECT_EQ(d.moved(), 0.0);
  EXPECT_EQ(d.window_start(), 5.0);
}

// Time moving by 2e-9 of its value per window is progress; by 0.5e-9 (round-off crawl) it is not.
TEST(StallDetector, TheBoundIsOneBillionthOfTheTime) {
  for (const auto& [step, stalls] : {std::pair{2e-9, false}, std::pair{0.5e-9, true}}) {
    StallDetector d;
    const double t0 = 1000.0;
    d.start(t0);
    const long long window = StallDetector::window(1);
    bool stalled = false;
    double t = t0;
    for (int w = 0; w < 3 && !stalled; ++w)
      for (long long k = 0; k < window && !stalled; ++k) {
        t += step * t0 / window;
        stalled = d.stalled(1, t);
      }
    EXPECT_EQ(stalled, stalls) << "relative step per window " << step;
  }
}

// A healthy run never stalls, and the window restarts where the last one ended.
TEST(StallDetector, ProgressRestartsTheWindow) {
  StallDetector d;
  d.start(0.0);
  double t = 0.0;
  for (int k = 0; k < 10 * StallDetector::window(3); ++k) {
    t += 1e-3;
    ASSERT_FALSE(d.stalled(3, t));
  }
  EXPECT_GT(d.window_start(), 0.0);
  EXPECT_NEAR(d.moved(), StallDetector::window(3) * 1e-3, 1e-9);
}
