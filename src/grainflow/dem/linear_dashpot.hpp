// Linear spring–dashpot with tangential history: the physics of LAMMPS `pair_style
// gran/hooke/history`, parameterised the same way (kn, kt, gamma_n, gamma_t, mu), so one case can
// be run in both codes. Damping is per unit effective mass: F_damp = -m_eff * gamma * v.
// The case keys and closed forms are in linear_dashpot.cpp.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "grainflow/dem/contact_law.hpp"

namespace grainflow::dem {

struct LinearDashpot {
  static constexpr std::string_view name = "linear_dashpot";
  static constexpr std::array<std::string_view, 4> keys = {"kn", "kt", "gamma_n", "gamma_t"};
  static constexpr std::array<std::string_view, 1> wall_keys = {"gamma_n"};
  static constexpr std::string_view stiffness_key = "kn";
  static constexpr bool calibrated_by_stiffness = false;  // kn at a fixed gamma_n would change e too

  struct Params {
    double kn = 0.0;        // N/m, normal stiffness
    double kt = 0.0;        // N/m, tangential stiffness
    double gamma_n = 0.0;   // 1/s, normal damping rate
    double gamma_t = 0.0;   // 1/s, tangential damping rate
    double friction = 0.0;  // Coulomb coefficient mu
  };

  struct State {
    Vec3 shear;  // m, accumulated tangential displacement, kept in the tangent plane
  };

  // Always inlined: the pair loop is mostly this function, and with the wall loops beside it the
  // compiler would otherwise call it (~10 % of a dense flow's step, measured).
  [[gnu::always_inline]] static ContactForce force(const Params& p, State& s, const ContactKinematics& c, double dt) {
    ContactForce out;
    // Hookean normal force with velocity damping. As in LAMMPS, the damped force may turn
    // slightly attractive at the end of a contact; restitution and duration have closed forms.
    out.normal = p.kn * c.overlap - c.effective_mass * p.gamma_n * c.normal_velocity;
    if (p.friction <= 0.0 && p.kt <= 0.0) return out;

    // Accumulate the slip, then rotate the stored displacement into the current tangent plane.
    s.shear += c.slip_velocity * dt;
    s.shear -= dot(s.shear, c.normal) * c.normal;
    const Vec3 damping = (c.effective_mass * p.gamma_t) * c.slip_velocity;
    Vec3 ft = -(p.kt * s.shear + damping);
    const double ft_magnitude = norm(ft);
    const double limit = p.friction * std::fabs(out.normal);
    if (ft_magnitude > limit) {
      // Sliding: rescale the stored displacement so spring plus dashpot sit on the Coulomb limit.
      if (norm2(s.shear) != 0.0) {
        const double ratio = limit / ft_magnitude;
        const Vec3 damping_displacement = damping * (1.0 / p.kt);
        s.shear = ratio * (s.shear + damping_displacement) - damping_displacement;
        ft *= ratio;
      } else {
        ft = Vec3{};
      }
    }
    out.tangential = ft;
    return out;
  }

  // The normal spring's 1/2 kn overlap^2 and the tangential spring's 1/2 kt |shear|^2.
  static double elastic_energy(const Params& p, const State& s, double overlap, double /*effective_radius*/) {
    return 0.5 * p.kn * overlap * overlap + 0.5 * p.kt * norm2(s.shear);
  }

  // [contact]: kn (required), kt (default 2/7 kn), gamma_n (0), gamma_t (gamma_n / 2, LAMMPS).
  static void read(TomlReader& table, ContactParameters& out);
  // [walls.FACE]: gamma_n (default the particles').
  static void read_wall(TomlReader& table, ContactParameters& out);
  static Params pair_params(const ContactConfig& contact, const SpeciesConfig& reference);
  static Params wall_params(const Params& pair, const ContactParameters& wall, double friction);
  // Overdamped (gamma_n >= 2 sqrt(kn / m_eff)): the spheres would never separate.
  static std::optional<ParameterProblem> problem(const Params& p, const HeadOnImpact& impact);
  static std::optional<ParameterProblem> species_problem(const std::vector<SpeciesConfig>&) { return std::nullopt; }

  // The damped oscillator's half period pi / sqrt(kn/m - gamma_n^2/4) and e = exp(-gamma_n t_c / 2).
  static BinaryContact binary_contact(const Params& p, const HeadOnImpact& impact);
  // The pair's contact in `collision_steps` steps.
  static double time_step(const Params& p, const HeadOnImpact& pair, int collision_steps);
  static double loading_stiffness(const Params& p, const HeadOnImpact&) { return p.kn; }
  static double tangential_stiffness(const Params& p, const HeadOnImpact&) { return p.kt; }
  static std::vector<CheckLine> describe(const Params& p, const HeadOnImpact& impact);
};

}  // namespace grainflow::dem
