// The TC model (edmd/tc_model.hpp): a collision within a contact duration of a particle's last one
// is a TC collision (elastic, smooth); a duration of 0 turns the model off.
#include <gtest/gtest.h>

#include "grainflow/edmd/tc_model.hpp"

using grainflow::edmd::TcModel;

TEST(TcModel, ACollisionSoonAfterTheLastIsElastic) {
  TcModel tc;
  tc.reset(3, 1e-3);
  EXPECT_FALSE(tc.recent(0, 0.0));  // never collided
  tc.note_collision(0, 2.0);
  EXPECT_TRUE(tc.recent(0, 2.0));
  EXPECT_TRUE(tc.recent(0, 2.0 + 0.9e-3));
  EXPECT_FALSE(tc.recent(0, 2.0 + 1.1e-3));
  EXPECT_FALSE(tc.recent(1, 2.0));  // per particle
  EXPECT_EQ(tc.last_collision(0), 2.0);
  EXPECT_EQ(tc.elastic()(5.0), 1.0);  // e = 1 at any impact speed
}

TEST(TcModel, AZeroContactDurationTurnsItOff) {
  TcModel tc;
  tc.reset(2, 0.0);
  tc.note_collision(1, 4.0);
  EXPECT_FALSE(tc.recent(1, 4.0));
}
