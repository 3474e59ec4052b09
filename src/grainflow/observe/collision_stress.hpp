// The stress tensor across a shear flow, strip by strip (Campbell 1982 sections 3.3-3.3.1), from an
// event-driven run's collisions and samples of its particles.
//
// Convention: P_ab is the flux of b-momentum across a plane normal to a, counted in the +a
// direction (the pressure tensor, minus the Cauchy stress): compressive normal stresses are
// positive, so P_yy is Campbell's tau_N (the weight above, in a chute); in a simple shear flow whose
// velocity u_x grows with y, P_yx = P_xy < 0 and Campbell's tau_s = -P_yx. Components are stored
// as a 3 x 3 array, index a * 3 + b; in 2D only x and y are used.
//
//  - collisional: each collision's impulse J on i, carried along the branch vector from j's centre
//    to i's, P_ab += (x_i - x_j)_a J_b, shared among the strips by the branch vector's length in
//    each (Irving-Kirkwood's line split); a wall collision carries its impulse along the segment
//    from the contact point on the wall to the particle's centre, and so does a particle rolling on
//    a wall, continuously (its weight's normal part, sampled). Per unit strip measure (area in 2D,
//    volume in 3D) and time.
//  - kinetic (streaming): sum m (v - u) (v - u) per unit measure, sampled, each particle counted in
//    the strip holding its centre, about the strip's long-term mean velocity u.
// Counting momentum where the branch vectors end, at the centres, makes each strip's momentum
// balance close exactly: in a steady flow the strip average of P_y. changes from strip to strip
// only by the weight in between (and a Couette cell without gravity has uniform P_yy and P_yx).
// Campbell's area-share profiles (profiles.csv) smooth the same fields over a particle's width.
#pragma once

#include <array>
#include <vector>

#include "grainflow/core/vec3.hpp"
#include "grainflow/engine_api/collision_observer.hpp"
#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/observe/block_sums.hpp"
#include "grainflow/analysis/strip_grid.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

using Tensor3 = std::array<double, 9>;  // index a * 3 + b

struct StripStress {
  double lo = 0.0, hi = 0.0;                                    // m, strip bounds at the end of averaging
  Tensor3 collisional{}, kinetic{}, total{};                    // Pa (2D: N/m)
  Tensor3 collisional_error{}, kinetic_error{}, total_error{};  // standard errors (NaN: too few blocks)
  double collision_rate = 0.0;               // pair collisions with the contact point here, 1/(s m^D)
  double collision_rate_per_particle = 0.0;  // 1/s: 2 x those collisions per s / mean particle count
  double dissipation_rate = 0.0;             // W/m^D lost in those collisions
  double number = 0.0;                       // mean count of particle centres in the strip
  double mass_density = 0.0;                 // kg/m^D, of the centres in the strip
  Vec3 mean_velocity;                        // m/s, long-term mass mean of the centres in the strip
  Vec3 momentum_rate;                        // N/m^D: (momentum at the end - at the start) / time / measure
  Vec3 weight_row;                           // Pa: the weight-integral estimate of P_{axis,b} at the centre
};

class StressProfile {
 public:
  // `period`: the box length along the strips' axis when the box is periodic there (the strips
  // then span it and what leaves one end enters at the other), else 0.
  explicit StressProfile(int strips, double period = 0.0);

  // Starts averaging at `time`: momentum per strip now (for Campbell's rho u_t correction).
  // `ranks`: on several MPI ranks each adds its own particles (not ghosts) and contacts, and the
  // strips' sums are added over the ranks at each sample, so that every rank holds the whole.
  void begin(const StripGrid& grid, const ParticleStore& p, double time, const RankReduce& ranks = {});
  // A particle pair collision; `grid` as it is at the collision's time.
  void add(const StripGrid& grid, const engine_api::PairCollision& c);
  // A wall collision: the impulse runs from the contact point to the centre.
  void add(const StripGrid& grid, const engine_api::WallCollision& c);
  // A force acting through the interval from `contact` to `centre` (a particle rolling on a wall).
  void add_contact_force(const StripGrid& grid, const Vec3& centre, const Vec3& contact, const Vec3& force,
                         double duration);
  // Closes the interval since the previous sample (or begin) at `time`: the kinetic sample, with
  // every particle current.
  void sample(const StripGrid& grid, const ParticleStore& p, double time, const RankReduce& ranks = {});

  bool started() const { return started_; }
  long samples() const { return samples_; }
  double elapsed() const { return last_time_ - start_time_; }  // s, averaged so far
  int strips() const { return strips_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(started_, start_time_, last_time_, samples_, total_, interval_, blocks_, momentum_start_, momentum_end_,
       thickness_, measure_, lo_);
  }

  // Long-term averages. `top_row`: P_{axis,b} at the top of the strips (a top wall's measurement,
  // zero at a free surface), where the weight integral starts; `gravity` in m/s^2.
  std::vector<StripStress> averages(const Vec3& gravity, const Vec3& top_row) const;

 private:
  struct Sums {
    Tensor3 collisional{};         // sum share (x_i - x_j) (x) J / measure
    Tensor3 second{};              // over samples, sum m v (x) v / measure
    Vec3 momentum;                 // over samples, sum m v / measure
    double mass = 0.0;             // over samples, sum m / measure
    double number = 0.0;           // over samples, centres counted
    double collisions = 0.0;       // count / measure
    double collision_count = 0.0;  // count
    double dissipated = 0.0;       // J / measure
    Sums& operator+=(const Sums& o);
  };
  // visit(strip, fraction) over the strips the segment from y0 to y1 crosses (wrapped when periodic).
  template <class Visit>
  void for_each_share(const StripGrid& grid, double y0, double y1, Visit&& visit) const;
  int strip_of(const StripGrid& grid, double y) const;
  void add_segment(const StripGrid& grid, const Vec3& from, const Vec3& to, const Vec3& impulse);
  std::vector<Vec3> momentum_now(const StripGrid& grid, const ParticleStore& p) const;
  Tensor3 kinetic_of(const Sums& s, long samples, const Vec3& u) const;

  int strips_;
  double period_;
  bool started_ = false;
  double start_time_ = 0.0, last_time_ = 0.0;
  long samples_ = 0;
  std::vector<Sums> total_, interval_;
  BlockSums<Sums> blocks_;                             // per interval, weighted by its duration
  std::vector<Vec3> momentum_start_, momentum_end_;    // kg m/s per strip
  double thickness_ = 0.0, measure_ = 0.0, lo_ = 0.0;  // the strips at the last sample: m, m^D, m
};

}  // namespace grainflow::observe
