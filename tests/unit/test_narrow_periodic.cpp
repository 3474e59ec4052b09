// Periodic widths shorter than two contact cutoffs (Lan 1994 section 5.2: a 3 d cell, and the
// 100 d x 1 d cell): a sphere then meets several images of a neighbour, and its own images, each
// contact with its own history. The test of it all: a narrow cell must behave like the same
// material copied side by side into a cell twice as wide, where every contact is an ordinary one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <variant>

#include "grainflow/dem/engine_factory.hpp"
#include "test_support.hpp"

using namespace grainflow;

namespace {

constexpr double kDiameter = 0.003;

// Spheres falling onto a frictional floor, shaken from t = 0.1 s (Gamma = 3.6, so the packed
// spheres keep moving and the neighbour lists keep being rebuilt under touching contacts), in a cell `width` wide along
// x (periodic) and 4 d along z (periodic), listed in `rows`; `copies` side by side along x.
std::string cell_case(double width, const std::string& file) {
  return R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [)" +
         std::to_string(width) + R"(, 0.04, 0.012]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.0, -9.81, 0.0]
[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
[particles]
init = "file"
file = ")" +
         file + R"("
[contact]
model = "walton_braun"
k1 = 1.0e4
restitution = 0.8
friction = 0.5
[walls.ylo]
friction = 0.5
[drive]
face = "ylo"
amplitude = [0.0, 0.001, 0.0]
frequency = [0.0, 30.0, 0.0]
start = 0.1
ramp = 0.05
[run]
duration = 0.3
collision_steps = 20
)";
}

struct Sphere {
  double x, y, z, vx, vy, vz;
};

std::string rows_of(const std::vector<Sphere>& spheres, double width, int copies) {
  std::string rows;
  for (int c = 0; c < copies; ++c)
    for (const Sphere& s : spheres)
      rows += "glass," + std::to_string(s.x + c * width) + "," + std::to_string(s.y) + "," + std::to_string(s.z) + "," +
              std::to_string(s.vx) + "," + std::to_string(s.vy) + "," + std::to_string(s.vz) + "\n";
  return rows;
}

struct CellRun {
  ParticleStore particles;
  long multiple_image_contacts = 0;  // the most pairs touching at more than one image at once
  long rebuilds = 0;
};

// The spheres' states at time `until` (s).
CellRun run_cell(const std::vector<Sphere>& spheres, double width, int copies, double until) {
  const test::ParticleFile file("cell.csv", rows_of(spheres, width, copies));
  const CaseConfig c = load_case_from_string(cell_case(copies * width, file.path()), "cell.toml");
  auto engine = test::engine_for(c, 1);
  return std::visit(
      [&](auto& e) {
        CellRun out;
        const long steps = std::lround(until / e.state().time_step);
        for (long step = 0; step < steps; ++step) {
          e.step();
          const auto& pairs = e.pairs();
          long now = 0;
          for (std::size_t i = 0; i + 1 < pairs.offsets.size(); ++i)
            for (std::uint32_t k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k)
              for (std::uint32_t q = k + 1; q < pairs.offsets[i + 1]; ++q)
                now += pairs.partner[q] == pairs.partner[k] && e.contacts().pair_touching[k] &&
                       e.contacts().pair_touching[q];
          out.multiple_image_contacts = std::max(out.multiple_image_contacts, now);
        }
        out.particles = e.state().particles;
        out.rebuilds = e.statistics().rebuilds;
        return out;
      },
      engine);
}

// 24 spheres in pairs: A a quarter of the width across, B three quarters across and higher by h,
// so that A touches B and B's image one width away at once (centres 0.97 d apart, overlap 3 %);
// pairs 2 d apart in height, at z = 1 d and 3 d; random velocities of 0.1 m/s. They push apart,
// fall onto the floor and pack.
std::vector<Sphere> column(double width, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = std::sqrt(0.97 * 0.97 * kDiameter * kDiameter - 0.25 * width * width);
  std::vector<Sphere> out;
  for (int k = 0; k < 6; ++k)
    for (const double z : {1.0 * kDiameter, 3.0 * kDiameter}) {
      const double y = (1.0 + 2.0 * k) * kDiameter;
      out.push_back({0.25 * width, y, z, 0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng)});
      out.push_back({0.75 * width, y + h, z, 0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng)});
    }
  return out;
}

}  // namespace

// At t = 10 ms (1,900 steps, about 50 list rebuilds while the spheres, which start touching two
// images of a neighbour, push apart and collide): each sphere of the narrow cell and both its
// copies in the doubled cell agree. The two runs sum the same forces in other orders, so they part
// by round-off that the contacts amplify, smoothly: 3e-17, 2e-15, 3e-14, 3e-13 m at 0.5, 2, 5 and
// 10 ms (velocities 3e-13 ... 2e-10 m/s), chaos tenfold every few milliseconds (measured). 1e-11 m
// and 1e-8 m/s leave a margin of 30-50 over that and lie far below any missed image, doubled force
// or history kept for the wrong image, which move a sphere by a sizeable fraction of d.
constexpr double kUntil = 0.01;

TEST(NarrowPeriodicCell, BehavesLikeTheSameMaterialDoubledInACellTwiceAsWide) {
  for (const double width : {1.05 * kDiameter, 1.5 * kDiameter}) {
    const auto spheres = column(width, 7);
    const CellRun narrow_run = run_cell(spheres, width, 1, kUntil);
    const CellRun doubled_run = run_cell(spheres, width, 2, kUntil);
    const ParticleStore& narrow = narrow_run.particles;
    const ParticleStore& doubled = doubled_run.particles;
    RecordProperty("multiple_image_contacts_" + std::to_string(int(width / kDiameter * 100)),
                   std::to_string(narrow_run.multiple_image_contacts));
    EXPECT_GT(narrow_run.multiple_image_contacts, 0) << "width " << width << ": no pair touches at two images";
    EXPECT_GT(narrow_run.rebuilds, 20) << "width " << width;  // histories carried over many rebuilds
    ASSERT_EQ(narrow.size(), spheres.size());
    ASSERT_EQ(doubled.size(), 2 * spheres.size());
    std::vector<std::size_t> at(doubled.size());
    for (std::size_t i = 0; i < doubled.size(); ++i) at[doubled.id[i]] = i;
    double largest = 0.0;
    for (std::size_t i = 0; i < narrow.size(); ++i) {
      const std::uint32_t id = narrow.id[i];
      const Vec3 x = narrow.position[i];
      for (const std::uint32_t copy : {id, static_cast<std::uint32_t>(id + spheres.size())}) {
        const std::size_t j = at[copy];
        Vec3 d = doubled.position[j] - x;
        d.x -= width * std::nearbyint(d.x / width);  // the copies lie a width apart, modulo 2 widths
        d.z -= 0.012 * std::nearbyint(d.z / 0.012);
        largest = std::max(largest, norm(d));
        EXPECT_LT(norm(doubled.velocity[j] - narrow.velocity[i]), 1e-8) << "width " << width << ", sphere " << id;
        EXPECT_LT(norm(doubled.angular_velocity[j] - narrow.angular_velocity[i]), 1e-5) << "width " << width;
      }
    }
    EXPECT_LT(largest, 1e-11) << "width " << width;
  }
}
