// A hand-made state for the observers' unit tests: a box, particles placed and moving as a test
// says, walls on its faces, and the Frame and RunContext an observer is built from, in a private
// output folder removed afterwards.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "grainflow/config/case_config.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"

namespace grainflow::test {

// A wall type of some engine: the shared part first, then its own.
struct TestWall : FaceWall {
  double friction = 0.0;
};

struct ObserverFixture {
  CaseConfig c;
  ParticleStore particles;
  PeriodicBox box;
  std::vector<TestWall> walls;
  observe::Frame frame;
  io::JsonObject summary;
  std::vector<std::string> warnings;
  std::filesystem::path dir;

  // A 10 x 10 x 10 mm box, periodic in x and z, gravity along -y, particles of 1 mm.
  ObserverFixture()
      : dir(std::filesystem::path(testing::TempDir()) / ("grainflow_observer_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir);
    c.path = "test.toml";
    c.domain.lo = {0.0, 0.0, 0.0};
    c.domain.hi = {0.01, 0.01, 0.01};
    c.gravity = {0.0, -9.81, 0.0};
    SpeciesConfig s;
    s.name = "glass";
    s.diameter = 0.001;
    c.species = {s};
    box.lo = c.domain.lo;
    box.hi = c.domain.hi;
    box.periodic = {true, false, true};
  }
  ~ObserverFixture() {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }

  void add(std::uint32_t id, const Vec3& x, const Vec3& v, int species = 0) {
    ParticleStore::Record r{};
    r.position = x;
    r.velocity = v;
    r.radius = r.target_radius = 0.0005;
    r.mass = 1e-6;
    r.inv_mass = 1.0 / r.mass;
    r.inv_inertia = 1.0 / (0.4 * r.mass * r.radius * r.radius);
    r.species = species;
    r.id = id;
    r.motion = Motion::free;
    r.wall = -1;
    particles.push_back(r);
  }
  void add_wall(int face, double position, const Vec3& velocity = {}) {
    TestWall w;
    w.face = face;
    w.axis = face / 2;
    w.inward = face % 2 == 0 ? 1.0 : -1.0;
    w.position = position;
    w.velocity = velocity;
    walls.push_back(w);
  }

  observe::RunContext context(double time_step) const {
    observe::RunContext run;
    run.c = &c;
    run.dimension = 3;
    run.gravity_axis = 1;
    run.reference_diameter = c.species.front().diameter;
    run.time_step = time_step;
    run.directory = dir.string();
    run.comm = &parallel::Communicator::world();
    return run;
  }
  // The frame at `time`, after `step` steps of `time_step`.
  const observe::Frame& at(double time, long step = 0, double time_step = 0.0) {
    frame.particles = &particles;
    frame.box = &box;
    frame.walls = FaceWalls(walls);
    frame.time = time;
    frame.step = step;
    frame.time_step = time_step;
    return frame;
  }
  observe::OutputSink sink() { return observe::OutputSink{dir.string(), true, &summary, &warnings}; }
};

}  // namespace grainflow::test
