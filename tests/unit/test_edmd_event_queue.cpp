// The event queue of the event-driven engine (src/grainflow/edmd/event_queue.hpp): an indexed
// 4-ary min-heap with one entry per particle. Checked against a brute-force minimum over the same
// times after every change, for the sizes where the heap's shape has edge cases (empty, one node,
// a partly filled last level, a full level) and for long random update sequences.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "grainflow/edmd/event_queue.hpp"

using grainflow::edmd::EventQueue;

namespace {

// The particle with the smallest time; ties cannot occur with continuous random times.
std::uint32_t brute_minimum(const std::vector<double>& times) {
  return static_cast<std::uint32_t>(std::min_element(times.begin(), times.end()) - times.begin());
}

TEST(EventQueue, EmptyQueueIsEmpty) {
  std::vector<double> times;
  EventQueue q;
  q.reset(0, &times);
  EXPECT_TRUE(q.empty());
}

TEST(EventQueue, TopIsTheEarliestAfterResetForEveryShape) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t n : {1u, 2u, 3u, 4u, 5u, 6u, 20u, 21u, 85u, 86u, 341u, 1000u}) {
    std::vector<double> times(n);
    for (double& t : times) t = u(rng);
    EventQueue q;
    q.reset(n, &times);
    EXPECT_EQ(q.top(), brute_minimum(times)) << "n = " << n;
  }
}

// The engine's pattern: the top particle gets a later time, and sometimes another particle (its
// partner) gets an earlier or a later one. 10^5 changes on 1000 particles.
TEST(EventQueue, TopStaysTheEarliestThroughRandomUpdates) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::size_t n = 1000;
  std::vector<double> times(n);
  for (double& t : times) t = u(rng);
  EventQueue q;
  q.reset(n, &times);
  double now = 0.0;
  for (int step = 0; step < 100000; ++step) {
    const std::uint32_t top = q.top();
    ASSERT_EQ(top, brute_minimum(times)) << "step " << step;
    now = times[top];
    times[top] = now + u(rng);
    q.update(top);
    if (step % 3 == 0) {
      const auto other = static_cast<std::uint32_t>(rng() % n);
      times[other] = now + u(rng) * (step % 2 ? 0.01 : 2.0);  // earlier or later than before
      q.update(other);
    }
  }
}

TEST(EventQueue, NeverScheduledParticlesStayBehindScheduledOnes) {
  // The engine gives particles with nothing ahead an infinite time; they must never come first.
  std::vector<double> times = {std::numeric_limits<double>::infinity(), 3.0, std::numeric_limits<double>::infinity(),
                               1.0, 2.0};
  EventQueue q;
  q.reset(times.size(), &times);
  EXPECT_EQ(q.top(), 3u);
  times[3] = std::numeric_limits<double>::infinity();
  q.update(3);
  EXPECT_EQ(q.top(), 4u);
  times[0] = 0.5;
  q.update(0);
  EXPECT_EQ(q.top(), 0u);
}

}  // namespace
