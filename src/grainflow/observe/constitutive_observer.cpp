#include "grainflow/observe/constitutive_observer.hpp"

#include <cmath>
#include <limits>

#include "grainflow/analysis/constitutive_functions.hpp"
#include "grainflow/io/atomic_file.hpp"

namespace grainflow::observe {
namespace {

constexpr int YX = 3, YY = 4;  // Tensor3 indices a * 3 + b

}  // namespace

void write_constitutive(const std::string& path, const CaseConfig& c, int dimension,
                        const std::vector<StripKinematics>& strips, const std::vector<StripStress>& stresses,
                        bool wall_below, bool wall_above) {
  using namespace strip;
  const double density = c.species.front().density;  // rho_p: mass per disc area (2D) or sphere volume (3D)
  const double radius = 0.5 * c.species.front().diameter;
  io::write_atomically(path, [&](std::ostream& out) {
    out.precision(10);
    out << "# constitutive functions per strip (Campbell 1982 sections 3.1.1, 3.3.1): chi = P_yy / (rho_p sum_i "
           "<u_i'^2>), f_s = tau_s / (rho_p R^2 (du/dy)^2), f_N = P_yy / (rho_p R^2 (du/dy)^2); rho_p = "
        << density << ", R = " << radius << "\n";
    out << "# stresses measured from the collisions (stresses.csv); *_weight: from Campbell's weight integral instead; "
           "chi_local: with the fluctuations about the instantaneous strip mean (D temperature_lan) instead of the "
           "time mean; "
           "chi_elastic: an elastic gas's nu Z(nu) / D (Henderson discs, Carnahan-Starling spheres); "
           "solids_fraction_3d: "
           "4/(3 sqrt pi) nu^(3/2) in 2D (section 3.1), nu in 3D\n";
    out << "# usable_chi: not against a wall, nu >= " << kConstitutiveMinimumSolidsFraction
        << "; usable_f: also not plug flow and f_n_error < " << kConstitutiveMaximumRelativeError << " f_n\n";
    out << "# units: y m, velocity_variance m^2/s^2, stresses " << (dimension == 2 ? "N/m" : "Pa")
        << ", du_dy 1/s, the rest 1; *_error: standard errors\n";
    out << "strip,y,dimension,solids_fraction,solids_fraction_error,solids_fraction_3d,velocity_variance,"
           "velocity_variance_error,normal_stress,normal_stress_error,shear_stress,shear_stress_error,du_dy,du_dy_"
           "error,"
           "chi,chi_error,chi_elastic,f_s,f_s_error,f_n,f_n_error,weight_normal_stress,weight_shear_stress,chi_weight,"
           "f_s_weight,f_n_weight,chi_local,chi_local_error,plug_flow,usable_chi,usable_f\n";
    const std::size_t n = std::min(strips.size(), stresses.size());
    for (std::size_t k = 0; k < n; ++k) {
      const auto& x = strips[k].averages;
      const auto& p = stresses[k];
      analysis::ConstitutiveInputs m;
      m.solids_fraction = x.value[solids_fraction];
      m.solids_fraction_error = x.error[solids_fraction];
      m.velocity_variance = x.value[u_variance] + x.value[v_variance] + (dimension == 3 ? x.value[w_variance] : 0.0);
      m.velocity_variance_error =
          std::hypot(x.error[u_variance], x.error[v_variance], dimension == 3 ? x.error[w_variance] : 0.0);
      m.normal_stress = p.total[YY];
      m.normal_stress_error = p.total_error[YY];
      m.shear_stress = -p.total[YX];
      m.shear_stress_error = p.total_error[YX];
      m.du_dy = strips[k].du_dy;
      m.du_dy_error = strips[k].du_dy_error;
      const auto v = analysis::constitutive_functions(m, density, radius);
      analysis::ConstitutiveInputs w = m;  // Campbell's: the stresses from the weight above
      w.normal_stress = p.weight_row.y, w.normal_stress_error = 0.0;
      w.shear_stress = -p.weight_row.x, w.shear_stress_error = 0.0;
      const auto vw = analysis::constitutive_functions(w, density, radius);
      analysis::ConstitutiveInputs local = m;  // the fluctuations about the instantaneous strip mean (Lan's)
      local.velocity_variance = dimension * x.value[temperature_lan];
      local.velocity_variance_error = dimension * x.error[temperature_lan];
      const auto vl = analysis::constitutive_functions(local, density, radius);
      const double nu = m.solids_fraction;
      const bool at_wall = (k == 0 && wall_below) || (k + 1 == n && wall_above);
      const bool usable_chi = !at_wall && nu >= kConstitutiveMinimumSolidsFraction && std::isfinite(v.chi);
      const bool usable_f =
          usable_chi && !strips[k].plug_flow && v.f_n > 0.0 && v.f_n_error < kConstitutiveMaximumRelativeError * v.f_n;
      const double nu_3d = dimension == 2 ? analysis::equivalent_3d_solids_fraction(nu) : nu;
      const double values[] = {static_cast<double>(k),
                               x.centre,
                               static_cast<double>(dimension),
                               nu,
                               m.solids_fraction_error,
                               nu_3d,
                               m.velocity_variance,
                               m.velocity_variance_error,
                               m.normal_stress,
                               m.normal_stress_error,
                               m.shear_stress,
                               m.shear_stress_error,
                               m.du_dy,
                               m.du_dy_error,
                               v.chi,
                               v.chi_error,
                               analysis::elastic_gas_chi(nu, dimension),
                               v.f_s,
                               v.f_s_error,
                               v.f_n,
                               v.f_n_error,
                               w.normal_stress,
                               w.shear_stress,
                               vw.chi,
                               vw.f_s,
                               vw.f_n,
                               vl.chi,
                               vl.chi_error,
                               strips[k].plug_flow ? 1.0 : 0.0,
                               usable_chi ? 1.0 : 0.0,
                               usable_f ? 1.0 : 0.0};
      bool first = true;
      for (double value : values) out << (first ? "" : ",") << value, first = false;
      out << "\n";
    }
  });
}

void ConstitutiveObserver::write(const Frame& last, OutputSink& out) {
  if (!out.writes || profiles_->samples() == 0) return;
  const bool wall_below = last.walls.with_role(WallRole::shear_bottom) >= 0,
             wall_above = last.walls.with_role(WallRole::shear_top) >= 0;
  write_constitutive(out.directory + "/constitutive.csv", *c_, last.dimension, profiles_->strip_kinematics(),
                     stresses_->strip_stresses(), wall_below, wall_above);
}

}  // namespace grainflow::observe
