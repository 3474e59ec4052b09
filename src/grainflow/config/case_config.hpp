// Typed, validated contents of a case file (TOML). Every field is SI unless its comment says
// otherwise; defaults here are the documented defaults of docs/CASE_FILES.md.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "grainflow/config/contact_parameters.hpp"
#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/config/observer_tables.hpp"
#include "grainflow/core/vec3.hpp"

namespace grainflow {

enum class FaceKind { periodic, wall, bumpy, open };

// Faces are numbered axis*2 + side: 0 xlo, 1 xhi, 2 ylo, 3 yhi, 4 zlo, 5 zhi.
inline constexpr std::array<const char*, 6> kFaceNames = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi"};
inline constexpr int face_axis(int face) { return face / 2; }
inline constexpr bool face_is_high(int face) { return face % 2 == 1; }

struct EngineConfig {
  bool operator==(const EngineConfig&) const = default;  // the case writer's round-trip test
  std::string kind = "dem";
  int dimension = 3;
};

struct DomainConfig {
  bool operator==(const DomainConfig&) const = default;  // the case writer's round-trip test
  Vec3 lo, hi;                                           // m
  std::array<FaceKind, 6> faces{};                       // per face
  bool periodic(int axis) const { return faces[axis * 2] == FaceKind::periodic; }
  double length(int axis) const { return hi[axis] - lo[axis]; }
};

struct SpeciesConfig {
  bool operator==(const SpeciesConfig&) const = default;  // the case writer's round-trip test
  std::string name;
  double diameter = 0.0;         // m
  double density = 0.0;          // kg/m^3 (kg/m^2 in 2D)
  std::int64_t count = 0;        // particles placed by [particles].init
  bool frozen = false;           // fixed in place, felt by others (e.g. a rough chute base)
  double youngs_modulus = 0.0;   // Pa, optional: for the Hertz-equivalent K1 (eqs. 2-5-5..2-5-9)
  double poisson_ratio = -1.0;   // optional, with youngs_modulus
  std::optional<Vec3> position;  // m: the one particle of this species starts here (init = random;
                                 // e.g. Lan's large sphere at the centre of the floor, section 5.2)
  // m: this species' own placement region (init = random), in place of [particles]'s; e.g. a rough
  // chute base of frozen spheres drawn at random in a thin layer, as Silbert et al. (2001) made theirs
  std::optional<Vec3> region_lo, region_hi;
  double mass(int dimension) const;  // kg, one sphere (3D) or disc (2D: density per area)
};

struct ParticlesConfig {
  bool operator==(const ParticlesConfig&) const = default;  // the case writer's round-trip test
  std::string init = "random";                              // random | lattice | file
  std::string file;                                         // with init = "file", resolved against the case's folder
  double initial_temperature = 0.0;                         // m^2/s^2
  std::uint64_t seed = 1;
  std::optional<Vec3> region_lo, region_hi;  // m, where random / lattice particles go
  // s, radius expansion of section 2.2 (init = random); < 0: not given, two fall times over the
  // reference diameter or 200 contact durations, whichever is longer (dem::DerivedQuantities)
  double expansion_time = -1.0;
  double lattice_spacing = 1.02;  // in diameters of the largest species (init = lattice)
  std::string lattice = "cubic";  // edmd: cubic (square in 2D) | fcc (3D; lattice_spacing = nearest-neighbor distance)
  double lattice_jitter = 0.0;    // edmd lattice: random displacement, as a fraction of the gap
  Vec3 initial_velocity;          // m/s, added to every moving particle
  std::string initial_profile = "uniform";  // uniform | couette (linear from the lo wall to the hi wall's speed)
                                            // | campbell_chute (listing COL007's profile, max = initial_velocity)
};

struct ContactConfig {
  bool operator==(const ContactConfig&) const = default;  // the case writer's round-trip test
  std::string model;      // a registered law (dem/contact_law_registry.hpp); absent: the first
  double friction = 0.0;  // Coulomb coefficient mu between particles, for every law
  // Rolling resistance, for every law (dem/rolling_resistance.hpp): "none" without rolling_friction,
  // else constant_torque | epsd (the default).
  std::string rolling_model = "none";
  double rolling_friction = 0.0;    // mu_r: the torque's cap is mu_r R* F_n
  double rolling_damping = 0.3;     // eta_r, epsd: the dashpot's fraction of critical (Ai et al. 2011)
  double rolling_stiffness = 2.25;  // c_k, epsd: k_r = c_k k_n mu_r^2 R*^2 (Iwashita & Oda, 3D)
  ContactParameters parameters;     // the law's own keys, as its file reads them
};

// Event-driven collisions (engine.kind = "edmd"), Campbell 1982 sections 2.11-2.12.
struct CollisionConfig {
  bool operator==(const CollisionConfig&) const = default;  // the case writer's round-trip test
  double restitution = 1.0;                                 // particle-particle normal restitution (constant law)
  std::string restitution_law = "constant";  // constant | campbell (e = (1 + exp(-3 dv / velocity_scale)) / 2)
  double velocity_scale = 0.0;               // m/s, campbell law; 0 = sqrt(g R) of the first species
  double elastic_speed = 0.0;                // m/s, impacts slower than this are elastic (stops inelastic collapse)
  double rolling_speed = 0.0;                // m/s, a wall rebound slower than this starts rolling (section 2.14.2);
                                             // default 1e-4 sqrt(g R) under gravity, 0 without
  double contact_duration = 0.0;             // s, TC model: a collision within this time of a particle's last one is
                                             // elastic; default 1e-4 sqrt(R/g) under gravity, 0 without
  double tangential_restitution = -1.0;      // -1 smooth, 0 Campbell's rough rule, +1 elastic rough
  // Campbell's guard (listings COL001/COL002): after a collision the pair is pushed apart to
  // (1 + gap) (R_i + R_j) and a particle to (1 + gap) R from a wall. 0: none (the TC model guards).
  double separation_gap = 0.0;
  double wall_restitution = 1.0;  // default for walls
  double inertia_factor = 0.0;    // q = (k/R)^2; 0 = 0.5 (discs) in 2D, 0.4 (solid spheres) in 3D
};

// Pressure-controlled Couette walls (Campbell 1982 section 2.14.3, listing COL002): the walls at
// ylo and yhi move apart or together so the measured normal stress approaches its target.
struct ServoConfig {
  bool operator==(const ServoConfig&) const = default;  // the case writer's round-trip test
  bool enabled = false;
  double normal_stress = 0.0;   // target, N/m in 2D (force per length), Pa in 3D
  bool keep_shear_rate = true;  // wall speeds follow the gap: U_T / H stays at its start value
  // Which walls' speeds follow the gap: "top", as listing COL002 (the bottom wall stays at rest; the
  // top wall's jumps heat its side a little), or "both", symmetrically about the walls' mean velocity.
  std::string shear_rate_walls = "top";
  bool scale_width = true;         // periodic width follows the gap: the aspect ratio stays fixed
  long long every_collisions = 0;  // update after this many collisions; 0 = 3 N
  double gap_change = 0.0;         // m, or after this gap change; 0 = 0.1 R
  double interval = 0.0;           // s, or once this long has passed; 0 = never
};

struct WallConfig {
  bool operator==(const WallConfig&) const = default;  // the case writer's round-trip test
  double restitution = -1.0;                           // edmd walls; < 0: collision.wall_restitution
  double friction = -1.0;                              // < 0: the particles' value (also for the bumps)
  double rolling_friction = -1.0;                      // dem, mu_r; < 0: the particles' value (also for the bumps)
  ContactParameters contact;         // dem walls: the contact law's own wall keys (also for the bumps)
  std::string condition = "smooth";  // edmd walls: smooth | rough | no_slip (Campbell's Couette walls)
  Vec3 velocity;                     // m/s, constant velocity of the wall (a drive adds to it)
  // bumpy walls: fixed half-spheres centred on the wall plane (section 2.6.3)
  double bump_diameter = 0.0;      // m; 0 = diameter of the first species
  std::string lattice = "square";  // square | triangular
  double spacing = 0.0;            // m, centre-to-centre; 0 = bump_diameter
};

// [geometry.motion]: a [[geometry]] wall's rigid motion, a translation at `velocity` (plus the case's
// [drive] with `drive`) and a rotation at `angular_velocity` about the axis through `origin`
// (right-handed; the origin moves with the translation).
struct GeometryMotionConfig {
  bool operator==(const GeometryMotionConfig&) const = default;  // the case writer's round-trip test
  Vec3 velocity;          // m/s
  Vec3 angular_velocity;  // rad/s
  Vec3 origin;            // m, at t = 0
  bool drive = false;     // follows [drive] (Lan's vibration) besides `velocity`
  bool moves() const { return drive || velocity != Vec3{} || angular_velocity != Vec3{}; }
};

// One [[geometry]] wall: a wall of a registered type (walls/wall_types.hpp) anywhere in the box.
struct GeometryConfig {
  bool operator==(const GeometryConfig&) const = default;  // the case writer's round-trip test
  std::string name;  // unique; names its rows in geometry.csv and its snapshot files
  std::string type;  // a registered wall type (walls/wall_types.hpp)
  GeometryKeys keys;       // the type's own keys
  WallConfig material;     // friction, rolling_friction and the contact law's wall keys, as [walls.FACE]
  GeometryMotionConfig motion;
};

// An [[insertion]]: particles of one species put into a region, non-overlapping with what is there.
struct InsertionConfig {
  bool operator==(const InsertionConfig&) const = default;  // the case writer's round-trip test
  std::string name;
  std::string species;
  long count = 0;      // a total (0: by rate)
  double rate = 0.0;   // particles per second (0: by count)
  Vec3 region_lo, region_hi;  // m, a box
  std::string inside;  // or the inside of a [[geometry]] of this name (its box, clear of its surface)
  Vec3 velocity;       // m/s
  double start = 0.0;  // s
};

// An [[outlet]]: particles whose centre enters its box are removed and counted (discharge.csv).
struct OutletConfig {
  bool operator==(const OutletConfig&) const = default;  // the case writer's round-trip test
  std::string name;
  Vec3 region_lo, region_hi;  // m
  std::string reinsert;       // an [[insertion]]'s name: each removed particle goes back through it
  bool has_bed = false;       // bed_lo, bed_hi given: a box in the bed, away from the orifice,
  Vec3 bed_lo, bed_hi;        // m, where the bulk solids fraction is measured
};

struct DriveConfig {
  bool operator==(const DriveConfig&) const = default;  // the case writer's round-trip test
  bool enabled = false;
  std::string preset;  // "" | rotary (eq. 4-1-1: equal amplitudes, phases 0, 2pi/3, 4pi/3)
  int face = 2;        // ylo; -1: no face (a [[geometry]] wall with motion.drive takes the drive)
  Vec3 amplitude;      // m, displacement amplitude per axis
  Vec3 frequency;      // Hz per axis
  Vec3 phase;          // rad per axis
  double start = 0.0;  // s, pouring time before shaking
  double ramp = 1.0;   // s, linear amplitude ramp after start
};

struct RunConfig {
  bool operator==(const RunConfig&) const = default;  // the case writer's round-trip test
  double duration = 0.0;                              // s
  double time_step = 0.0;                             // s; 0 = eq. (2-5-4) with collision_steps
  int collision_steps = 15;                           // n of eq. (2-5-4)
  double skin = -1.0;                                 // m, Verlet skin; < 0: 0.15 largest diameter
  double halt_overlap = 0.0;                          // stop when max overlap / d exceeds this (0 = never; seeds: 0.01)
  double clog_time = -1.0;  // s: with [[outlet]]s, stop when none has let a particle out for this long (0 = never; < 0: 50 sqrt(d / g))
  int sort_every = 20;                                // neighbor rebuilds between spatial re-sorts (0 = never)
  long long collisions = 0;  // edmd: stop after this many particle collisions (0 = run the duration)
  // edmd: "continuous", or "campbell": Campbell's runs of at most `segment_collisions` collisions
  // (COL001/COL002 count them in an I5 field), each judged by the section 2.5 convergence check;
  // the first converged segment's averages are the run's, and it stops there.
  std::string protocol = "continuous";
  long long segment_collisions = 99999;
  int max_segments = 20;
};

struct OutputConfig {
  bool operator==(const OutputConfig&) const = default;  // the case writer's round-trip test
  double interval = 0.01;                                // s between time-series rows
  double snapshot_interval = 0.0;                        // s between VTU snapshots (0 = none)
  double checkpoint_interval =
      0.0;                        // s between checkpoint.h5 rewrites, and one at the end (0 = only on SIGINT/SIGTERM)
  double profile_interval = 0.0;  // s between profile samples (0 = interval / 10)
  double average_start = 0.0;     // s, long-term averages start here
  long long average_start_collisions = 0;  // edmd: ... and not before this many particle collisions
  bool collision_stresses = true;  // edmd: stresses.csv, walls.csv, collision_angles.csv (a per-collision observer)
  bool stresses = false;           // dem: stresses.csv, walls.csv from the contact forces, sampled
  double zone_thickness = 0.0;     // m, profile zones along gravity (0 = reference species diameter)
  // Bed height and bulk solids fraction (Lan 1994 section 4.2; observe/bed_surface.hpp):
  double bed_gap_fraction = 0.05;     // a zone above the densest one emptier than this ends the bed
  double bed_surface_fraction = 0.1;  // the surface is the highest d/10 slice at least this full
};

// [tracers]: position, velocity and coordination number histories of chosen particles (Lan 1994
// section 5.2, the large sphere; Figs. A5.12-A5.17); tracers.csv.
struct TracersConfig {
  bool operator==(const TracersConfig&) const = default;  // the case writer's round-trip test
  bool enabled = false;
  std::vector<std::uint32_t> particles;  // ids
  std::vector<std::string> species;      // every particle of these species
  double start = 0.0;                    // s
  double interval = 0.0;                 // s; 0 = 1 / (20 f) with a drive along gravity, else output.interval
};

// [trajectory]: samples of chosen particles written to trajectory.h5. DEM: windowed velocities and
// unwrapped positions for correlation functions and diffusion (Lan 1994 sections 3.2-3.3). EDMD:
// instantaneous states (positions, velocities, spins, walls) for Campbell's velocity and pair
// distributions (Campbell 1982 section 3.4).
struct TrajectoryConfig {
  bool operator==(const TrajectoryConfig&) const = default;  // the case writer's round-trip test
  bool enabled = false;
  double start = -1.0;                   // s; < 0: output.average_start
  double window = 0.0;                   // s, t_s (dem); 0: (collision_steps / 2) time steps, Lan's half collision time
  double interval = 0.0;                 // s between instantaneous samples (edmd); 0: the rest of the run / samples
  long long samples = 2000;              // windows to record
  long long max_lag = 0;                 // samples, the longest lag `grainflow analyze` uses; 0: samples / 2
  std::vector<std::uint32_t> particles;  // ids to follow; empty: every free particle
};

// [coarse_grain]: density, solid fraction, velocity, kinetic and contact stress on a 3D grid of
// cells over the box, by MercuryCG's method (observe/coarse_grain_field.hpp), time-averaged;
// coarse_grained.vti.
struct CoarseGrainConfig {
  bool operator==(const CoarseGrainConfig&) const = default;  // the case writer's round-trip test
  bool enabled = false;
  std::string kernel = "gaussian";  // "gaussian" or "lucy"
  double width = 0.0;               // m, the Gaussian's standard deviation; 0 = half the reference diameter
  double cutoff = 0.0;              // m, Lucy's support radius; 0 = sqrt(3) reference diameters (the same spread)
  std::array<int, 3> cells{};       // per axis; 0 = cells one standard deviation of the kernel wide
  double start = -1.0;              // s; < 0: output.average_start
  double interval = 0.0;            // s between samples; 0: output.profile_interval (else output.interval / 10)

  // The kernel's size (width or cutoff), its standard deviation, and the grid, defaults resolved.
  // In 2D the kernel spreads over the x-y plane and the grid has one cell along z.
  double kernel_size(double reference_diameter) const;
  double standard_deviation(double reference_diameter, int dimension) const;
  std::array<int, 3> grid(const Vec3& box_length, double reference_diameter, int dimension) const;
};

// The standard deviation of one coordinate under Lucy's kernel (1 + 3q)(1 - q)^3, q = r / cutoff,
// over a ball of that cutoff: <r^2> is c^2 / 4 in 3D and 5 c^2 / 28 in 2D, shared by the coordinates.
double lucy_standard_deviation(double cutoff, int dimension);

// One explicitly given particle (init = "file").
struct InitialParticle {
  bool operator==(const InitialParticle&) const = default;  // the case writer's round-trip test
  std::string species;
  Vec3 position, velocity, angular_velocity;  // m, m/s, rad/s
  double diameter = 0.0;                      // m; 0 = the species' diameter
};

struct CaseConfig {
  bool operator==(const CaseConfig&) const = default;  // the case writer's round-trip test
  std::string path;                                    // the case file, as given
  std::vector<std::string> overrides;  // --set KEY=VALUE assignments applied on top of the file, in order
  EngineConfig engine;
  DomainConfig domain;
  Vec3 gravity{0.0, -9.81, 0.0};
  std::vector<SpeciesConfig> species;
  ParticlesConfig particles;
  ContactConfig contact;
  CollisionConfig collision;
  ServoConfig servo;
  double lees_edwards_rate = 0.0;  // 1/s, [lees_edwards] shear_rate: unbounded simple shear (flow x, gradient y)
  std::array<WallConfig, 6> walls;
  std::vector<GeometryConfig> geometry;  // [[geometry]] walls, in the order given
  std::vector<InsertionConfig> insertions;  // [[insertion]]
  std::vector<OutletConfig> outlets;        // [[outlet]]
  DriveConfig drive;
  RunConfig run;
  OutputConfig output;
  TrajectoryConfig trajectory;
  ObserverTables observer_tables;  // the tables of observers that read their own (observer_schema.hpp)
  TracersConfig tracers;
  CoarseGrainConfig coarse_grain;
  std::vector<InitialParticle> initial_particles;  // read from particles.file
};

// An event-driven trajectory's sampling grid: the first sample (trajectory.start, else
// output.average_start) and the spacing (trajectory.interval, else the rest of the run spread
// evenly over the samples: t_k = start + k interval, k = 0 .. samples - 1, the last before the end).
double trajectory_start(const CaseConfig& c);
double edmd_trajectory_interval(const CaseConfig& c);

}  // namespace grainflow
