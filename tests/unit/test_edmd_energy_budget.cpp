// The event-driven engine's energy budget (engine_api/energy_budget.hpp): the work of gravity along
// the periodic axes, of moving walls (the servo's) and of sliding images (Lees-Edwards rows, a
// Couette cell's width) equals the change of kinetic + rotational + potential energy plus what the
// collisions dissipated. Between events every flight conserves energy exactly, and each event's
// share is measured where it happens (the loss in the frame of the wall or image met, the work as
// W . J), so the budget closes to round-off: summed over ~10^5 events of energies ~1e-16 relative
// round-off each, 1e-9 of the input is a wide bound, while one missing term (a wall's work, the
// seam's velocity jump, the last impact before rolling) leaves a residual of order 1e-3 or more.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "grainflow/edmd/edmd_engine.hpp"
#include "grainflow/run/case_loader.hpp"
#include "test_support.hpp"

using namespace grainflow;

namespace {

constexpr double kRoundOff = 1e-9;

// cases/campbell1982/chute_30deg.toml without comments: 40 rough discs on a rough bottom wall
// under gravity inclined 30 degrees, open top.
const char* kChute = R"(
[engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [9.6, 80.0, 1.0]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.5, -0.8660254037844386, 0.0]
[[species]]
name = "disc"
diameter = 2.0
density = 0.3183098861837907
count = 40
[particles]
init = "lattice"
region_hi = [9.6, 24.0, 1.0]
lattice_spacing = 1.2
lattice_jitter = 0.3
initial_velocity = [3.0, 0.0, 0.0]
initial_temperature = 0.01
seed = 1982
[collision]
restitution = 0.6
roughness = "rough"
inertia_factor = 0.5
rolling_speed = 1.0e-4
contact_duration = 1.0e-4
[walls.ylo]
restitution = 0.8
condition = "rough"
[run]
duration = 300.0
)";

// cases/campbell1982/couette_noslip.toml's cell: 40 rough discs between no-slip walls, the servo
// moving both walls and the width, the shear rate kept.
const char* kCouette = R"(
[engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [9.6, 24.0, 1.0]
boundary = { x = "periodic", y = "wall", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "disc"
diameter = 2.0
density = 0.3183098861837907
count = 40
[particles]
init = "lattice"
lattice_spacing = 1.2
lattice_jitter = 0.3
initial_profile = "couette"
initial_temperature = 0.001
seed = 1982
[collision]
restitution = 0.6
roughness = "rough"
inertia_factor = 0.5
contact_duration = 1.0e-4
[walls.ylo]
restitution = 0.8
condition = "no_slip"
[walls.yhi]
restitution = 0.8
condition = "no_slip"
velocity = [1.0, 0.0, 0.0]
[servo]
normal_stress = 9.84375e-4
[run]
duration = 3000.0
)";

// Unbounded simple shear: 400 discs at area fraction 0.35, Lees-Edwards boundaries at rate 0.1.
std::string sheared_gas(double restitution, const char* roughness) {
  return "[engine]\nkind = \"edmd\"\ndimension = 2\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [30.0, 30.0, 1.0]\n"
         "boundary = { x = \"periodic\", y = \"periodic\", z = \"periodic\" }\n[gravity]\nvector = [0.0, 0.0, 0.0]\n"
         "[[species]]\nname = \"disc\"\ndiameter = 1.0\ndensity = 1.2732395447351628\ncount = 400\n"
         "[particles]\ninit = \"random\"\ninitial_temperature = 0.01\nseed = 3\n[collision]\nrestitution = " +
         std::to_string(restitution) + "\nroughness = \"" + roughness +
         "\"\n[lees_edwards]\nshear_rate = 0.1\n[run]\nduration = 200.0\n";
}

template <int Dim>
engine_api::EnergyBudget run_budget(const CaseConfig& c, double until) {
  edmd::EdmdEngine<Dim> e(edmd::build_edmd_state(c));
  e.advance_to(until);
  return e.energy_budget();
}

}  // namespace

// A chute: gravity's work along the flow is the input; the bottom wall stands still.
TEST(EdmdEnergyBudget, ClosesInAChute) {
  const auto b = run_budget<2>(load_case_from_string(kChute, "chute.toml"), 300.0);
  EXPECT_GT(b.gravity_work, 0.0);
  EXPECT_GT(b.dissipated, 0.0);
  EXPECT_EQ(b.wall_work, 0.0);
  EXPECT_EQ(b.boundary_work, 0.0);
  EXPECT_NEAR(b.input() - b.change - b.dissipated, 0.0, kRoundOff * b.input());
}

// A servo Couette cell, walls moving along x (shear) and y (servo), the width following the gap:
// the walls' work drives it, the images moving with the width rate do some too.
TEST(EdmdEnergyBudget, ClosesInAServoCouetteCell) {
  for (const char* walls : {"both", "top"}) {
    const CaseConfig c =
        load_case_from_string(kCouette, "couette.toml", {std::string("servo.shear_rate_walls=\"") + walls + "\""});
    const auto b = run_budget<2>(c, 3000.0);
    EXPECT_GT(b.wall_work, 0.0) << walls;
    EXPECT_NE(b.boundary_work, 0.0) << walls;
    EXPECT_GT(b.dissipated, 0.0) << walls;
    EXPECT_NEAR(b.input() - b.change - b.dissipated, 0.0, kRoundOff * b.input()) << walls;
  }
}

// Lees-Edwards shear: the boundaries' work (seam collisions and crossings) heats the gas. Elastic
// smooth discs dissipate nothing and keep every joule of it; inelastic rough ones dissipate it.
TEST(EdmdEnergyBudget, ClosesUnderLeesEdwardsShear) {
  {
    const auto b = run_budget<2>(load_case_from_string(sheared_gas(1.0, "smooth"), "le.toml"), 200.0);
    EXPECT_GT(b.boundary_work, 0.0);
    EXPECT_NEAR(b.dissipated, 0.0, kRoundOff * b.boundary_work);
    EXPECT_NEAR(b.change, b.boundary_work, kRoundOff * b.boundary_work);
  }
  {
    const auto b = run_budget<2>(load_case_from_string(sheared_gas(0.8, "rough"), "le.toml"), 200.0);
    EXPECT_GT(b.boundary_work, 0.0);
    EXPECT_GT(b.dissipated, 0.0);
    EXPECT_NEAR(b.input() - b.change - b.dissipated, 0.0, kRoundOff * b.input());
  }
}

// Campbell's scheme instead of the TC model: every collision inelastic and rough, each pair pushed
// apart to 2.00001 R and each wall rebound to 1.00001 R. The shifts move particles against gravity;
// their energy is the separation's input, and the budget still closes to round-off.
TEST(EdmdEnergyBudget, ClosesWithCampbellsReseparation) {
  const CaseConfig c =
      load_case_from_string(kChute, "chute.toml", {"collision.contact_duration=0", "collision.separation_gap=1.0e-5"});
  const auto b = run_budget<2>(c, 300.0);
  EXPECT_NE(b.separation_work, 0.0);
  EXPECT_NEAR(b.input() - b.change - b.dissipated, 0.0, kRoundOff * b.input());
}

// Discs of R = 1 and unit mass in a 40 x 40 cell, periodic along x, with e = 0.5 and Campbell's
// re-separation gap of 1e-5 R, started from `rows` (species,x,y,z,vx,vy,vz), with `y_boundary` along
// y and the tables in `extra`.
namespace {
CaseConfig reseparation_case(const std::string& rows, const std::string& y_boundary, const std::string& extra,
                             double duration) {
  const test::ParticleFile file("discs.csv", rows);
  const std::string text = R"(
[engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [40.0, 40.0, 1.0]
boundary = { x = "periodic", y = )" +
                           y_boundary + R"(, z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "disc"
diameter = 2.0
density = 0.3183098861837907
[particles]
init = "file"
file = ")" + file.path() + R"("
[collision]
restitution = 0.5
separation_gap = 1.0e-5
)" + extra +
                           "[run]\nduration = " + std::to_string(duration) + "\n";
  return load_case_from_string(text, "discs.toml");
}
}  // namespace

// Two discs meet head on at relative speed 2: after the collision at t = 1 they are (1 + 1e-5) 2R
// apart, then separate at e x 2 = 1: at t = 2 their distance is 2.00002 + 1.
TEST(EdmdReseparation, APairLeavesItsCollisionAtTheListingsDistance) {
  const CaseConfig c = reseparation_case("disc,10,20,0.5,1,0,0\ndisc,14,20,0.5,-1,0,0\n", "\"periodic\"", "", 2.0);
  edmd::EdmdEngine<2> e(edmd::build_edmd_state(c));
  e.advance_to(2.0);
  const auto& p = e.state().particles;
  EXPECT_EQ(e.counters().collisions, 1);
  EXPECT_NEAR(std::fabs(p.position[1].x - p.position[0].x), 2.0 * (1.0 + 1e-5) + 1.0, 1e-12);
}

// The same at a wall: a disc meets the floor at speed 1 at t = 4 with e_w = 0.5; the rebound
// leaves its centre 1.00001 R from the wall, so at t = 6 it stands at 1.00001 + 0.5 x 2. Without
// the shift it would stand at 2 exactly: the 1e-5 is a million times the bound.
TEST(EdmdReseparation, AWallReboundLeavesTheDiscAtTheListingsDistance) {
  const CaseConfig c =
      reseparation_case("disc,10,5,0.5,0,-1,0\n", "[\"wall\", \"open\"]", "[walls.ylo]\nrestitution = 0.5\n", 6.0);
  edmd::EdmdEngine<2> e(edmd::build_edmd_state(c));
  e.advance_to(6.0);
  EXPECT_EQ(e.counters().wall_collisions, 1);
  EXPECT_NEAR(e.state().particles.position[0].y, 1.0 + 1e-5 + 0.5 * 2.0, 1e-12);
}
