// The contract every registered contact law keeps, tested over the registry itself: a head-on
// impact integrated with the law's force reproduces its own closed-form duration and restitution
// (between particles and against a wall), Newton's third law, frame invariance with history, the
// Coulomb bound, the time-step bound, its case table read back from the case writer, linear
// momentum conserved by the engine through an oblique frictional impact, the normal force as the
// slope of its elastic energy, and the engine's forces independent of the thread count. A new law is tested by
// one Example specialisation below; without it this file does not compile.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <variant>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/config/case_writer.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

// A typical [contact] table of each law (friction included) and a [walls.ylo] table of its keys.
template <class Law>
struct Example;
template <>
struct Example<WaltonBraun> {
  static constexpr const char* contact = "k1 = 1.0e5\nrestitution = 0.8\nfriction = 0.4";
  static constexpr const char* wall = "restitution = 0.6";
  static constexpr const char* species = "";
};
template <>
struct Example<LinearDashpot> {
  static constexpr const char* contact = "kn = 1.0e5\ngamma_n = 300.0\nfriction = 0.4";
  static constexpr const char* wall = "gamma_n = 900.0";
  static constexpr const char* species = "";
};
template <>
struct Example<HertzMindlin> {
  static constexpr const char* contact = "restitution = 0.8\nfriction = 0.4";
  static constexpr const char* wall = "restitution = 0.6\nyoungs_modulus = 2.0e8";
  static constexpr const char* species = "youngs_modulus = 1.0e8\npoisson_ratio = 0.25\n";
};
// Adhesion weak enough that both test speeds (0.1 and 1 m/s) rebound (sticking below ~0.03 m/s).
template <>
struct Example<Jkr> {
  static constexpr const char* contact = "restitution = 0.8\nsurface_energy = 0.05\nfriction = 0.4";
  static constexpr const char* wall = "restitution = 0.6\nyoungs_modulus = 2.0e8";
  static constexpr const char* species = "youngs_modulus = 1.0e8\npoisson_ratio = 0.25\n";
};

constexpr double kDiameter = 0.002, kDensity = 2500.0;
const double kMass = kDensity * M_PI / 6.0 * kDiameter * kDiameter * kDiameter;

std::string case_text(std::string_view model, const std::string& contact, const std::string& wall,
                      const std::string& particles = "init = \"random\"", int count = 20,
                      const std::string& species = "") {
  std::ostringstream t;
  t << "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
    << "boundary = { x = \"periodic\", y = \"wall\", z = \"periodic\" }\n"
    << "[gravity]\nvector = [0.0, 0.0, 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = " << kDiameter << "\ndensity = " << kDensity << "\ncount = " << count
    << "\n"
    << species << "[particles]\n"
    << particles << "\n"
    << "[contact]\nmodel = \"" << model << "\"\n"
    << contact << "\n"
    << "[walls.ylo]\n"
    << wall << "\n"
    << "[run]\nduration = 1.0\n";
  return t.str();
}

template <class Law>
CaseConfig example_case() {
  return load_case_from_string(
      case_text(Law::name, Example<Law>::contact, Example<Law>::wall, "init = \"random\"", 20, Example<Law>::species),
      "example.toml");
}

struct Impact {
  double duration = 0.0, restitution = 0.0;
};

// Two bodies of effective mass m_eff meet head-on at speed v0: velocity Verlet on the relative
// coordinate with the law's normal force, `steps` steps per closed-form contact duration. The
// contact lasts while the law exerts a force: until the overlap returns to zero (an adhesive law's
// neck: to its detach overlap), or earlier where the force ends at a residual overlap (a latching
// law); that end is placed to within dt / 2.
template <class Law>
Impact integrate_impact(const typename Law::Params& p, const HeadOnImpact& impact, int steps) {
  const double dt = Law::binary_contact(p, impact).duration / steps;
  const double effective_mass = impact.effective_mass, v0 = impact.speed;
  typename Law::State state{};
  ContactKinematics k;
  k.normal = {1.0, 0.0, 0.0};
  k.effective_mass = effective_mass;
  k.effective_radius = impact.effective_radius;
  double overlap = 0.0, speed = v0;  // closing speed, > 0 while approaching
  double force = 0.0, time = 0.0, last_force_time = 0.0;
  auto acceleration = [&](double dt_step) {
    k.overlap = overlap;
    k.normal_velocity = -speed;
    force = Law::force(p, state, k, dt_step).normal;
    return force / effective_mass;  // pushes the bodies apart
  };
  double end = 0.0;
  if constexpr (CohesiveContactLaw<Law>) end = Law::detach_overlap(p, impact.effective_radius);
  double a = acceleration(0.0);
  for (int i = 0; i < 100 * steps; ++i) {
    const double half = speed - 0.5 * dt * a;
    const double next = overlap + half * dt;
    if (next <= end) {
      const double crossing = time + dt * (overlap - end) / (overlap - next);
      return {force != 0.0 ? crossing : last_force_time + 0.5 * dt, (half - 0.5 * dt * a) / -v0};
    }
    overlap = next;
    speed = half;
    a = acceleration(dt);
    speed -= 0.5 * dt * a;
    time += dt;
    if (force != 0.0) last_force_time = time;
  }
  return {};
}

// A random unit vector and a random rotation (Rodrigues), for invariance tests.
Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  const Vec3 v{g(rng), g(rng), g(rng)};
  return v * (1.0 / norm(v));
}
Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {
  return v * std::cos(angle) + cross(axis, v) * std::sin(angle) + axis * (dot(axis, v) * (1.0 - std::cos(angle)));
}

// A sequence of kinematics: overlap rising then falling (loading and unloading), slip turning and
// reversing, so tangential memory, reversals and sliding are all exercised.
std::vector<ContactKinematics> contact_history(std::mt19937_64& rng, double effective_mass, double scale) {
  std::vector<ContactKinematics> out;
  const Vec3 n = random_unit(rng);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    ContactKinematics k;
    k.normal = n;
    k.overlap = scale * 1e-3 * std::sin(M_PI * (i + 0.5) / 200.0);
    k.normal_velocity = -scale * 0.5 * std::cos(M_PI * (i + 0.5) / 200.0);
    Vec3 slip{u(rng), u(rng), u(rng)};
    slip -= dot(slip, n) * n;
    k.slip_velocity = slip * (scale * (i % 50 < 25 ? 1.0 : -0.7));
    k.effective_mass = effective_mass;
    k.effective_radius = 0.25 * kDiameter;
    out.push_back(k);
  }
  return out;
}

template <class List>
struct GtestTypesOf;
template <ContactLaw... Laws>
struct GtestTypesOf<ContactLawList<Laws...>> {
  using type = ::testing::Types<Laws...>;
};

template <class Law>
class ContactLawContract : public ::testing::Test {};
TYPED_TEST_SUITE(ContactLawContract, GtestTypesOf<RegisteredContactLaws>::type);

// The integrated impact and the closed form agree to O((pi/n)^2) for a smooth force, to O(gamma dt)
// where a force jumps at first touch (a dashpot), and the end of a force that stops at a residual
// overlap is placed to within dt / 2: with n = 20000 steps all are below 2.5e-5 of the duration,
// and 1e-4 leaves a factor 4. Pair (m_eff = m/2) and wall (m_eff = m, the wall's own keys).
TYPED_TEST(ContactLawContract, ImpactMatchesItsClosedForms) {
  using Law = TypeParam;
  const CaseConfig c = example_case<Law>();
  const auto pair = Law::pair_params(c.contact, c.species.front());
  const auto wall = Law::wall_params(pair, c.walls[2].contact, 0.0);
  const HeadOnImpact pair_at_rest{0.5 * kMass, 0.25 * kDiameter, 0.0}, wall_at_rest{kMass, 0.5 * kDiameter, 0.0};
  for (const auto& [params, conditions] : {std::pair{pair, pair_at_rest}, std::pair{wall, wall_at_rest}}) {
    for (double v0 : {0.1, 1.0}) {
      HeadOnImpact impact = conditions;
      impact.speed = v0;
      const BinaryContact closed = Law::binary_contact(params, impact);
      ASSERT_TRUE(std::isfinite(closed.duration) && closed.duration > 0.0);
      const Impact run = integrate_impact<Law>(params, impact, 20000);
      EXPECT_NEAR(run.duration, closed.duration, 1e-4 * closed.duration) << "v0 = " << v0;
      EXPECT_NEAR(run.restitution, closed.restitution, 1e-4) << "v0 = " << v0;
    }
  }
  // The wall table's key takes effect: the example walls are more dissipative than the pairs.
  const HeadOnImpact at_speed{0.5 * kMass, 0.25 * kDiameter, 1.0};
  EXPECT_LT(Law::binary_contact(wall, at_speed).restitution, Law::binary_contact(pair, at_speed).restitution);
  EXPECT_FALSE(Law::problem(pair, at_speed));
}

// F_ij = -F_ji at every step of a history: j sees the opposite normal and slip. Both sides are
// the same arithmetic up to signs, so they agree to rounding (1e-12 of the force).
TYPED_TEST(ContactLawContract, NewtonsThirdLawWithHistory) {
  using Law = TypeParam;
  const CaseConfig c = example_case<Law>();
  const auto p = Law::pair_params(c.contact, c.species.front());
  std::mt19937_64 rng(7);
  typename Law::State seen_by_i{}, seen_by_j{};
  for (const ContactKinematics& k : contact_history(rng, 0.5 * kMass, 1.0)) {
    ContactKinematics mirrored = k;
    mirrored.normal = -1.0 * k.normal;
    mirrored.slip_velocity = -1.0 * k.slip_velocity;
    const ContactForce fi = Law::force(p, seen_by_i, k, 1e-6);
    const ContactForce fj = Law::force(p, seen_by_j, mirrored, 1e-6);
    const double scale = 1e-12 * (std::fabs(fi.normal) + norm(fi.tangential) + 1e-30);
    EXPECT_NEAR(fi.normal, fj.normal, scale);  // along opposite normals: opposite vectors
    EXPECT_LE(norm(fi.tangential + fj.tangential), scale);
  }
}

// Rotating every input vector rotates the tangential force and leaves the normal force unchanged,
// through the memory the law keeps (rounding: 1e-12 of the force).
TYPED_TEST(ContactLawContract, FrameInvariantWithHistory) {
  using Law = TypeParam;
  const CaseConfig c = example_case<Law>();
  const auto p = Law::pair_params(c.contact, c.species.front());
  std::mt19937_64 rng(11);
  const Vec3 axis = random_unit(rng);
  const double angle = 1.234;
  typename Law::State plain{}, rotated{};
  for (const ContactKinematics& k : contact_history(rng, 0.5 * kMass, 1.0)) {
    ContactKinematics r = k;
    r.normal = rotate(k.normal, axis, angle);
    r.slip_velocity = rotate(k.slip_velocity, axis, angle);
    const ContactForce f = Law::force(p, plain, k, 1e-6);
    const ContactForce g = Law::force(p, rotated, r, 1e-6);
    const double scale = 1e-12 * (std::fabs(f.normal) + norm(f.tangential) + 1e-30);
    EXPECT_NEAR(f.normal, g.normal, scale);
    EXPECT_LE(norm(rotate(f.tangential, axis, angle) - g.tangential), scale);
  }
}

// Coulomb: |F_t| <= mu |F_n| at every step (an adhesive law: mu times its sliding load), for slips
// small (sticking) and large (sliding).
TYPED_TEST(ContactLawContract, TangentialForceWithinCoulombBound) {
  using Law = TypeParam;
  const CaseConfig c = example_case<Law>();
  const auto p = Law::pair_params(c.contact, c.species.front());
  std::mt19937_64 rng(3);
  for (double slip_scale : {1e-3, 1.0, 100.0}) {
    typename Law::State s{};
    bool slid = false;
    for (ContactKinematics k : contact_history(rng, 0.5 * kMass, 1.0)) {
      k.slip_velocity *= slip_scale;
      const ContactForce f = Law::force(p, s, k, 1e-6);
      const double limit = c.contact.friction * sliding_load<Law>(p, f.normal, k.effective_radius);
      EXPECT_LE(norm(f.tangential), limit * (1.0 + 1e-12) + 1e-300);
      slid = slid || (limit > 0.0 && norm(f.tangential) > 0.999 * limit);
    }
    if (slip_scale == 100.0) {
      EXPECT_TRUE(slid) << "large slips must reach the Coulomb limit";
    }
  }
}

// The law's step bound resolves its own binary contact in at least n steps.
TYPED_TEST(ContactLawContract, TimeStepResolvesContact) {
  using Law = TypeParam;
  const CaseConfig c = example_case<Law>();
  const auto p = Law::pair_params(c.contact, c.species.front());
  const HeadOnImpact pair{0.5 * kMass, 0.25 * kDiameter, 1.0};
  for (int n : {5, 15, 20, 50}) {
    const double dt = Law::time_step(p, pair, n);
    EXPECT_GE(Law::binary_contact(p, pair).duration / dt, n * (1.0 - 1e-12)) << "n = " << n;
  }
}

// Its keys come back from the case writer unchanged, and derive() and `check` take its forms.
TYPED_TEST(ContactLawContract, CaseTableRoundTripAndDerivedQuantities) {
  using Law = TypeParam;
  const CaseConfig c = example_case<Law>();
  const CaseConfig again = load_case_from_string(write_case_toml(c), "again.toml");
  EXPECT_EQ(again.contact, c.contact);
  EXPECT_EQ(again.walls[2].contact, c.walls[2].contact);
  const DerivedQuantities d = derive(c);
  const auto p = Law::pair_params(c.contact, c.species.front());
  const HeadOnImpact pair{0.5 * d.reference_mass, 0.25 * d.reference_diameter, d.impact_speed};
  EXPECT_EQ(d.model, Law::name);
  EXPECT_EQ(d.contact_duration, Law::binary_contact(p, pair).duration);
  EXPECT_EQ(d.time_step, Law::time_step(p, pair, c.run.collision_steps));
  EXPECT_EQ(d.law_lines.size(), Law::describe(p, pair).size());
}

// Another law's key is named as such, and a key of its own is required where the law says so.
TYPED_TEST(ContactLawContract, OtherLawsKeysAreRefusedByName) {
  using Law = TypeParam;
  for_each_contact_law([&]<ContactLaw Other>() {
    for (std::string_view key : Other::keys) {
      if (std::find(Law::keys.begin(), Law::keys.end(), key) != Law::keys.end()) continue;
      const std::string contact = std::string(Example<Law>::contact) + "\n" + std::string(key) + " = 1.0";
      try {
        load_case_from_string(case_text(Law::name, contact, "", "init = \"random\"", 20, Example<Law>::species),
                              "other.toml");
        ADD_FAILURE() << key << " of " << Other::name << " was accepted by " << Law::name;
      } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "contact." + std::string(key));
        EXPECT_NE(e.reason().find(std::string(Other::name)), std::string::npos) << e.what();
      }
    }
  });
}

// Through the engine: two spheres meet obliquely (friction slides and spins them); the total
// momentum is the same before and after to rounding, as the engine applies each contact's force to
// both partners with opposite signs.
TYPED_TEST(ContactLawContract, EngineConservesMomentumInObliqueImpact) {
  using Law = TypeParam;
  const test::ParticleFile csv("oblique_" + std::string(Law::name) + ".csv",
                               "glass,0.008,0.0095,0.01,0.5,0,0.1\nglass,0.0101,0.0105,0.01,-0.3,0.05,0\n");
  const std::string particles = "init = \"file\"\nfile = \"" + csv.path() + "\"";
  const CaseConfig c = load_case_from_string(
      case_text(Law::name, Example<Law>::contact, "", particles, 0, Example<Law>::species), "oblique.toml");
  auto engine = test::engine_for(c, 1);
  std::visit(
      [&](auto& e) {
        auto& p = e.state().particles;
        auto momentum = [&] { return p.mass[0] * p.velocity[0] + p.mass[1] * p.velocity[1]; };
        const Vec3 before = momentum();
        const double scale = norm(p.mass[0] * p.velocity[0]) + norm(p.mass[1] * p.velocity[1]);
        long contacts = 0;
        for (int k = 0; k < 4000; ++k) {
          e.step();
          contacts = std::max(contacts, e.statistics().contacts);
        }
        EXPECT_GT(contacts, 0) << "the spheres never touched";
        EXPECT_GT(norm(p.angular_velocity[0]), 0.0) << "friction never acted";
        EXPECT_LE(norm(momentum() - before), 1e-12 * scale);
      },
      engine);
}

// The normal force is the slope of the energy the law says its springs hold: loaded at rest to a
// peak overlap of 1 % of the diameter, then on the way back (the reversible branch of a law with
// hysteresis: Walton-Braun's K2 line, JKR's attached neck), F_n(delta) = dU/d delta at zero normal
// and slip velocity. The central difference with h = 1e-4 delta errs by ~1e-8 relatively (and
// round-off by ~1e-12), so 1e-6 is tight, while a wrong prefactor in U (8/15 against 2/5, a lost
// 1/2) is off by 10 % or more. The energy budget rests on this.
TYPED_TEST(ContactLawContract, NormalForceIsTheSlopeOfItsElasticEnergy) {
  using Law = TypeParam;
  const CaseConfig c = example_case<Law>();
  const auto p = Law::pair_params(c.contact, c.species.front());
  const double peak = 0.01 * kDiameter, radius = 0.25 * kDiameter;
  auto at_rest = [&](double overlap) {
    ContactKinematics k;
    k.normal = {0.0, 1.0, 0.0};
    k.overlap = overlap;
    k.effective_mass = 0.5 * kMass;
    k.effective_radius = radius;
    return k;
  };
  typename Law::State s{};
  for (int i = 1; i <= 100; ++i) Law::force(p, s, at_rest(peak * i / 100.0), 1e-7);  // loading
  for (double fraction : {0.95, 0.8, 0.6, 0.4}) {
    const double overlap = fraction * peak, h = 1e-4 * overlap;
    typename Law::State copy = s;
    const double force = Law::force(p, copy, at_rest(overlap), 0.0).normal;
    const double slope =
        (Law::elastic_energy(p, s, overlap + h, radius) - Law::elastic_energy(p, s, overlap - h, radius)) / (2.0 * h);
    ASSERT_GT(std::fabs(force), 0.0) << "no force at " << fraction << " of the peak overlap";
    EXPECT_NEAR(slope, force, 1e-6 * std::fabs(force)) << Law::name << " at " << fraction << " of the peak overlap";
  }
}

// 600 spheres on a square lattice at contact spacing, with friction, on a shaken floor, in the
// law's example units.
std::string pile_case(std::string_view model, const std::string& contact, const std::string& wall,
                      const std::string& species) {
  const double d = kDiameter;
  std::ostringstream t;
  t << "[engine]\nkind = \"dem\"\ndimension = 3\n"
    << "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [" << 8 * d << ", " << 20 * d << ", " << 8 * d << "]\n"
    << "boundary = { x = \"periodic\", y = [\"wall\", \"open\"], z = \"periodic\" }\n"
    << "[gravity]\nvector = [0.0, -9.81, 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = " << d << "\ndensity = " << kDensity << "\ncount = 600\n"
    << species << "[particles]\ninit = \"lattice\"\nlattice_spacing = 1.0\nregion_hi = [" << 8 * d << ", " << 14 * d
    << ", " << 8 * d << "]\ninitial_temperature = 1.0e-3\nseed = 3\n"
    << "[contact]\nmodel = \"" << model << "\"\n"
    << contact << "\n"
    << "[walls.ylo]\n"
    << wall << "\nfriction = 0.4\n"
    << "[drive]\nface = \"ylo\"\namplitude = [0.0, " << 0.7 * d << ", 0.0]\nfrequency = [0.0, 20.0, 0.0]\n"
    << "[run]\nduration = 0.01\n";
  return t.str();
}

struct PileForces {
  std::vector<Vec3> force, torque;
  long contacts = 0;
};

// The forces an engine on `threads` threads computes from `state`, after `steps` more steps.
PileForces pile_forces(const CaseConfig& c, const DemState& state, int threads, int steps) {
  auto engine = make_engine(c, state, threads);
  PileForces f;
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < steps; ++k) e.step();
        f.force = e.state().particles.force;
        f.torque = e.state().particles.torque;
        f.contacts = e.statistics().contacts;
      },
      engine);
  return f;
}

double largest_norm(const std::vector<Vec3>& v) {
  double m = 0.0;
  for (const Vec3& x : v) m = std::max(m, norm(x));
  return m;
}

// The engine's forces do not depend on the thread count (each thread adds to its own range of
// particles and buffers its shares for the others'): the pile settled for 400 one-thread steps,
// then evaluated with 1, 2 and 3 threads, gives every particle the same force and torque up to the
// order of summation (1e-12 of the largest), and the same contacts, at once and 5 steps later.
// (Long runs would test nothing: a contact begun one step earlier through round-off restarts its
// tangential history, so frictional runs part visibly whatever the order.)
TYPED_TEST(ContactLawContract, ForcesDoNotDependOnTheThreadCount) {
  using Law = TypeParam;
  const CaseConfig c = load_case_from_string(
      pile_case(Law::name, Example<Law>::contact, Example<Law>::wall, Example<Law>::species), "threads_test.toml");
  DemState state;
  auto settling = make_engine(c, build_dem_state(c), 1);
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < 400; ++k) e.step();
        state = e.state();
      },
      settling);
  for (int steps : {0, 5}) {
    const PileForces one = pile_forces(c, state, 1, steps);
    ASSERT_GT(one.contacts, 500) << Law::name << ": the pile should be in contact (600 particles)";
    const double f_scale = largest_norm(one.force), t_scale = largest_norm(one.torque);
    for (int threads : {2, 3}) {
      const PileForces many = pile_forces(c, state, threads, steps);
      EXPECT_EQ(one.contacts, many.contacts) << Law::name << ", " << threads << " threads";
      double f_diff = 0.0, t_diff = 0.0;
      for (std::size_t i = 0; i < one.force.size(); ++i) {
        f_diff = std::max(f_diff, norm(one.force[i] - many.force[i]));
        t_diff = std::max(t_diff, norm(one.torque[i] - many.torque[i]));
      }
      EXPECT_LE(f_diff, 1e-12 * f_scale) << Law::name << ", " << threads << " threads, step " << steps;
      EXPECT_LE(t_diff, 1e-12 * t_scale) << Law::name << ", " << threads << " threads, step " << steps;
    }
  }
}

TEST(ContactLawRegistry, UnknownModelListsEveryRegisteredLaw) {
  try {
    load_case_from_string(case_text("nonsense", "k1 = 1.0", ""), "unknown.toml");
    FAIL() << "an unknown contact model was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "contact.model");
    for_each_contact_law(
        [&]<ContactLaw Law>() { EXPECT_NE(e.reason().find(std::string(Law::name)), std::string::npos); });
  }
}

}  // namespace
