// Numerical faults of an event-driven run: a clock that stops advancing (inelastic
// collapse, Zeno bounces), a state turned non-finite, a particle gone through a wall. The collapse
// message is built on the rare path where the engine's progress check fails; the other checks are
// O(N) and run at output times, never per event.
#pragma once

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/edmd/edmd_state.hpp"

namespace grainflow::edmd {

namespace fault_detail {
inline std::string format(const char* fmt, double a) {
  char text[64];
  std::snprintf(text, sizeof text, fmt, a);
  return text;
}
inline std::string vec(const Vec3& v) {
  char text[128];
  std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", v.x, v.y, v.z);
  return text;
}
inline bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace fault_detail

// What the engine knows when its clock stalls: the window of events, the last event's particles
// (j < 0: none; wall >= 0: a wall event) and the particles that collided within the window.
struct Stall {
  double time = 0.0, moved = 0.0;
  long long events = 0;
  std::uint32_t i = 0;                   // particle id of the last event
  long long j = -1;                      // partner's id, or -1
  int wall_face = -1;                    // face of the wall hit, or -1
  std::vector<std::uint32_t> colliders;  // ids of the particles that collided in the window (at most 8)
  std::size_t collider_count = 0;
};

inline std::string stall_message(const Stall& s, const EdmdState& state) {
  using fault_detail::format;
  std::string text = "simulated time stopped advancing at t = " + format("%.17g", s.time) + " s: the last " +
                     std::to_string(s.events) + " events moved it by " + format("%.3g", s.moved) +
                     " s; the last event ";
  if (s.j >= 0) text += "was a collision between particles " + std::to_string(s.i) + " and " + std::to_string(s.j);
  else if (s.wall_face >= 0)
    text += "was particle " + std::to_string(s.i) + " hitting the " + kFaceNames[s.wall_face] + " wall";
  else text += "involved particle " + std::to_string(s.i);
  if (s.collider_count > 0) {
    text += "; " + std::to_string(s.collider_count) + " particle(s) collided within those events (";
    for (std::size_t k = 0; k < s.colliders.size(); ++k) text += (k ? ", " : "") + std::to_string(s.colliders[k]);
    if (s.collider_count > s.colliders.size()) text += ", ...";
    text += ")";
  }
  text +=
      "; likely cause: inelastic collapse (or ever faster bounces on a wall, or a resting contact): use the TC model, "
      "collision.contact_duration (now " +
      format("%.4g", state.contact_duration) +
      " s), or a velocity-dependent restitution, collision.restitution_law = \"campbell\" or collision.elastic_speed "
      "(now " +
      format("%.4g", state.restitution.elastic_speed) + " m/s), and under gravity collision.rolling_speed (now " +
      format("%.4g", state.rolling_speed) + " m/s)";
  return text;
}

inline std::string describe_particle(const EdmdState& s, std::size_t i) {
  const ParticleStore& p = s.particles;
  return "particle " + std::to_string(p.id[i]) + " at " + fault_detail::vec(p.position[i]) + " m moving at " +
         fault_detail::vec(p.velocity[i]) + " m/s";
}

// Throws RunError when a particle's position or velocity is not finite, or a particle lies more
// than one diameter beyond a wall's plane. Particles must be current (after advance_to).
inline void check_faults(const EdmdState& s) {
  using fault_detail::format;
  const ParticleStore& p = s.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!fault_detail::finite(p.position[i]) || !fault_detail::finite(p.velocity[i]))
      throw RunError("non-finite state: " + describe_particle(s, i) + " at t = " + format("%.9g", s.time) +
                     " s; likely cause: a collision of two particles at the same place (zero separation) or a "
                     "wall or servo update that produced an infinite speed");
  for (const EdmdWall& wall : s.walls) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double gap = wall.distance(p.position[i], s.time);
      if (gap < -2.0 * p.radius[i])
        throw RunError(describe_particle(s, i) + " went through the " + kFaceNames[wall.face] +
                       " wall at t = " + format("%.9g", s.time) + " s: its centre lies " + format("%.4g", -gap) +
                       " m beyond the wall (more than a diameter); likely cause: a missed wall event, from round-off "
                       "in a grazing or resting contact (set collision.rolling_speed) or a wall moving faster than the "
                       "particles can be predicted against");
    }
  }
}

}  // namespace grainflow::edmd
