// FaceWall and FaceWalls: the wall geometry both engines share, seen through a view of any wall type.
#include <gtest/gtest.h>

#include "grainflow/dem/dem_state.hpp"
#include "grainflow/edmd/edmd_state.hpp"

namespace grainflow {
namespace {

TEST(FaceWall, PlaneMovesAtItsNormalSpeedAndMeasuresDistanceInward) {
  FaceWall top;
  top.face = 3;  // yhi
  top.axis = 1;
  top.inward = -1.0;
  top.position = 2.0;
  top.since = 1.0;
  top.velocity = {5.0, -0.5, 0.0};  // sliding along x does not move the plane
  EXPECT_DOUBLE_EQ(top.at(3.0), 2.0 - 0.5 * 2.0);
  EXPECT_DOUBLE_EQ(top.normal().y, -1.0);
  EXPECT_DOUBLE_EQ(top.normal().x, 0.0);
  // A point 0.25 below the plane at t = 1 is 0.25 inside; behind the plane the distance is negative.
  EXPECT_DOUBLE_EQ(top.distance({0.0, 1.75, 0.0}, 1.0), 0.25);
  EXPECT_DOUBLE_EQ(top.distance({0.0, 2.5, 0.0}, 1.0), -0.5);
}

// The view strides over each engine's own wall type and finds the same faces and planes.
template <class Wall>
void expect_view_of(std::vector<Wall> walls) {
  walls.resize(3);
  for (int k = 0; k < 3; ++k) {
    walls[k].face = 2 * k + 1;
    walls[k].axis = k;
    walls[k].position = 10.0 + k;
  }
  const FaceWalls view(walls);
  ASSERT_EQ(view.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(&view[k], static_cast<const FaceWall*>(&walls[k]));
  EXPECT_EQ(view.on_face(3), 1);
  EXPECT_EQ(view.on_face(2), -1);
  double sum = 0.0;
  for (const FaceWall& w : view) sum += w.position;
  EXPECT_DOUBLE_EQ(sum, 33.0);
  walls[2].position = 20.0;  // the view follows the walls as they move
  EXPECT_DOUBLE_EQ(view[2].position, 20.0);
}

TEST(FaceWalls, ViewsSoftSphereWalls) { expect_view_of(std::vector<dem::DemWall>{}); }
TEST(FaceWalls, ViewsEventDrivenWalls) { expect_view_of(std::vector<edmd::EdmdWall>{}); }

TEST(FaceWalls, SoftSphereWallMovedToATimeIsThereThen) {
  dem::DemWall floor;
  floor.face = 2;
  floor.axis = 1;
  floor.base_position = 1e-3;
  floor.motion = dem::WallMotion({0.0, 0.2, 0.0}, nullptr);  // rising at 0.2 m/s
  floor.move_to(0.004);
  EXPECT_DOUBLE_EQ(floor.at(0.004), 1e-3 + 0.2 * 0.004);
  EXPECT_DOUBLE_EQ(floor.since, 0.004);
  // A constant velocity extrapolates exactly.
  EXPECT_NEAR(floor.at(0.005), 1e-3 + 0.2 * 0.005, 1e-18);
}

}  // namespace
}  // namespace grainflow
