// Numerical faults of a soft-sphere run: a state turned non-finite, a particle gone
// through a wall, an overlap beyond run.halt_overlap. Each check is O(N) (O(pairs) for the overlap)
// and runs at output times or on a rare path, never inside the step loop; each builds a message
// naming the particle(s), the simulated time and the likely cause, with numbers.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "grainflow/config/case_config.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/dem/dem_state.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/dem/neighbor_list.hpp"

namespace grainflow::dem {

// A non-finite position or velocity, found by the engine (which does not know the case): the run
// appends the likely cause (time_step_cause) before reporting it.
class NonFiniteState : public RunError {
 public:
  using RunError::RunError;
};

// What the other ranks of an MPI run throw when one rank finds a non-finite state inside a step.
inline constexpr const char* kFaultOnAnotherRank = "non-finite state on another MPI rank";

namespace fault_detail {
inline std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, fmt, a, b, c);
  return text;
}
inline std::string vec(const Vec3& v) { return format("(%.6g, %.6g, %.6g)", v.x, v.y, v.z); }
inline bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
// The normal stiffness as the user sets it: a spring constant (k1, kn), or for a law whose
// stiffness is the material's the linear spring its impact is equivalent to.
inline std::string stiffness_now(const DerivedQuantities& d) {
  const std::string value = format("%.4g", d.normal_stiffness) + " N/m";
  return d.calibrated_by_stiffness ? d.stiffness_key + " = " + value
                                   : "an equivalent linear stiffness of " + value + " (from " + d.stiffness_key + ")";
}
// What reaching a linear stiffness `needed` asks of the case: the key's value, or for a Hertz
// material the factor on its modulus (the equivalent stiffness m* (v / delta_max)^2 grows as E^4/5).
inline std::string stiffness_needed(const DerivedQuantities& d, double needed) {
  if (d.calibrated_by_stiffness) return d.stiffness_key + " >= " + format("%.4g", needed) + " N/m";
  return d.stiffness_key + " raised " + format("%.3g", std::pow(needed / d.normal_stiffness, 1.25)) + "-fold";
}
}  // namespace fault_detail

// "particle 7 at (x, y, z) m moving at (vx, vy, vz) m/s".
inline std::string describe_particle(const DemState& s, std::size_t i) {
  const ParticleStore& p = s.particles;
  return "particle " + std::to_string(p.id[i]) + " at " + fault_detail::vec(p.position[i]) + " m moving at " +
         fault_detail::vec(p.velocity[i]) + " m/s";
}

// The engine's message for particle i with a non-finite position or velocity.
inline NonFiniteState non_finite_state(const DemState& s, std::size_t i) {
  return NonFiniteState("non-finite state: " + describe_particle(s, i) +
                        " at t = " + fault_detail::format("%.9g", s.time) + " s (step " + std::to_string(s.step) + ")");
}

// The first particle (by index) whose position or velocity is NaN or infinite.
inline std::optional<std::size_t> first_non_finite(const ParticleStore& p) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!fault_detail::finite(p.position[i]) || !fault_detail::finite(p.velocity[i])) return i;
  return std::nullopt;
}

// The likely cause of a blow-up: the time step against the contact law's bound (eq. 2-5-4 for
// Walton–Braun) with n = 20 steps per collision (Lan 1994), for the lightest moving species.
inline std::string time_step_cause(const DerivedQuantities& d) {
  std::string text =
      "likely cause: the time step dt = " + fault_detail::format("%.4g", d.time_step) + " s is too large for " +
      fault_detail::stiffness_now(d) + " (" + fault_detail::format("%.3g", d.steps_per_contact) +
      " steps per contact); the contact law's time-step bound with n = " + std::to_string(kLanCollisionSteps) +
      " steps per collision suggests dt <= " + fault_detail::format("%.4g", d.time_step_lan) + " s";
  text += d.time_step_from_case ? " (lower run.time_step or remove it)" : " (raise run.collision_steps)";
  return text;
}

// The engine's NonFiniteState with the likely cause added.
inline std::string with_cause(const NonFiniteState& fault, const DerivedQuantities& d) {
  return std::string(fault.what()) + "; " + time_step_cause(d);
}

// Throws RunError (with the cause) when any particle's position or velocity is not finite.
inline void check_finite(const DemState& s, const DerivedQuantities& d) {
  if (const auto i = first_non_finite(s.particles)) throw RunError(with_cause(non_finite_state(s, *i), d));
}

// A free particle more than one diameter beyond a wall's plane has gone through it.
struct Escape {
  std::size_t index = 0;
  int wall = 0;         // index into DemState::walls
  double beyond = 0.0;  // m, how far its centre lies behind the plane
};

// The smallest gap between x and the wall's surface (negative behind it), looking `reach` far.
inline double wall_gap(const DemWall& wall, const Vec3& x, double reach) { return walls::nearest_gap(wall.shape, x, reach); }

inline std::optional<Escape> first_escape(const DemState& s) {
  const ParticleStore& p = s.particles;
  for (std::size_t w = 0; w < s.walls.size(); ++w) {
    const DemWall& wall = s.walls[w];
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.motion[i] != Motion::free) continue;
      const double gap = wall_gap(wall, p.position[i], p.radius[i]);
      if (gap < -2.0 * p.radius[i]) return Escape{i, static_cast<int>(w), -gap};
    }
  }
  return std::nullopt;
}

// Throws RunError naming the particle, the face, the time and the likely cause when a particle
// has gone through a wall: the impact speed against the wall's stiffness and the time step.
inline void check_escape(const DemState& s, const DerivedQuantities& d) {
  const auto escape = first_escape(s);
  if (!escape) return;
  const ParticleStore& p = s.particles;
  const std::size_t i = escape->index;
  const DemWall& wall = s.walls[escape->wall];
  const double m = p.mass[i], r = p.radius[i];
  const double speed = norm(p.velocity[i]);
  // A linear spring stopped from speed v penetrates v sqrt(m / K1); to keep that below 1% of d
  // (Lan's criterion) K1 >= m (v / 0.01 d)^2.
  const double penetration = speed * std::sqrt(m / d.normal_stiffness);
  const double needed_k1 = m * std::pow(speed / (0.02 * r), 2);
  std::string text = describe_particle(s, i) + " went through the " + wall.name + " wall at t = " + fault_detail::format("%.9g", s.time) + " s: its centre lies " +
                     fault_detail::format("%.4g", escape->beyond) + " m beyond the wall (more than a diameter, " +
                     fault_detail::format("%.4g", 2.0 * r) +
                     " m); likely cause: too soft a wall or too large a time step "
                     "for the impact speed: at " +
                     fault_detail::format("%.4g", speed) + " m/s a wall with " + fault_detail::stiffness_now(d) +
                     " lets it in " + fault_detail::format("%.4g", penetration) +
                     " m; keeping that below 1% of d needs " + fault_detail::stiffness_needed(d, needed_k1) +
                     ", and dt = " + fault_detail::format("%.4g", d.time_step) + " s moves it " +
                     fault_detail::format("%.4g", speed * d.time_step) + " m per step";
  throw RunError(text);
}

// The touching pair (or particle and wall) with the largest overlap / smaller diameter now: one
// pass over the neighbour pairs and the walls, for the message of run.halt_overlap.
struct LargestOverlap {
  double ratio = 0.0;
  std::size_t i = 0, j = 0;
  int wall = -1;  // >= 0: particle i and that wall; else particles i and j
};

inline LargestOverlap largest_overlap(const DemState& s, const NeighborPairs& pairs) {
  const ParticleStore& p = s.particles;
  const auto shifts = s.box.shift_table();
  LargestOverlap best;
  for (std::size_t i = 0; i + 1 < pairs.offsets.size(); ++i)
    for (std::uint32_t k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
      const std::uint32_t j = pairs.partner[k];
      const double overlap = p.radius[i] + p.radius[j] - norm(p.position[i] - (p.position[j] + shifts[pairs.shift[k]]));
      const double ratio = overlap / (2.0 * std::min(p.radius[i], p.radius[j]));
      if (ratio > best.ratio) best = {ratio, i, j, -1};
    }
  for (std::size_t w = 0; w < s.walls.size(); ++w)
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.motion[i] != Motion::free) continue;
      const double ratio = (p.radius[i] - wall_gap(s.walls[w], p.position[i], p.radius[i])) / (2.0 * p.radius[i]);
      if (ratio > best.ratio) best = {ratio, i, i, static_cast<int>(w)};
    }
  return best;
}

// The message of run.halt_overlap: the bound, the pair overlapping most now, and the K1 that Lan's
// 1 % criterion asks for (a linear spring's overlap scales as K1^(-1/2)).
inline std::string overlap_halt_message(const DemState& s, const NeighborPairs& pairs, const DerivedQuantities& d,
                                        double max_ratio, double halt_overlap) {
  using fault_detail::format;
  std::string text = "maximum overlap / diameter " + format("%.4g", max_ratio) +
                     " exceeded run.halt_overlap = " + format("%.4g", halt_overlap) +
                     " before t = " + format("%.9g", s.time) + " s";
  const LargestOverlap now = largest_overlap(s, pairs);
  if (now.ratio > 0.0) {
    const auto& id = s.particles.id;
    text += now.wall >= 0 ? "; now the largest is between particle " + std::to_string(id[now.i]) + " and the " +
                                s.walls[now.wall].name + " wall"
                          : "; now the largest is between particles " + std::to_string(id[now.i]) + " and " +
                                std::to_string(id[now.j]);
    text += " (" + format("%.4g", now.ratio) + " of a diameter)";
  }
  text += "; likely cause: too soft a contact (" + fault_detail::stiffness_now(d) +
          ") for the impact speeds; Lan's 1 % criterion (overlap <= 0.01 d) suggests " +
          fault_detail::stiffness_needed(d, d.normal_stiffness * std::pow(max_ratio / 0.01, 2));
  if (halt_overlap != 0.01)
    text += " (" + fault_detail::stiffness_needed(d, d.normal_stiffness * std::pow(max_ratio / halt_overlap, 2)) +
            " for the halt bound)";
  text += ", or lower the impact speeds";
  return text;
}

// The checks made at each output time: a non-finite state, then a particle gone through a wall.
inline void check_faults(const DemState& s, const DerivedQuantities& d) {
  check_finite(s, d);
  check_escape(s, d);
}

}  // namespace grainflow::dem
