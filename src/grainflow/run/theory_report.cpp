#include "grainflow/run/theory_report.hpp"

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "grainflow/run/run_support.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/config/restitution_laws.hpp"
#include "grainflow/config/wall_conditions.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/flat_json_reader.hpp"

namespace grainflow::run {

namespace fs = std::filesystem;

TheoryInputs theory_inputs(const CaseConfig& c) {
  auto fail = [&](const std::string& key, const std::string& reason) {
    throw InputError(c.path, key, reason + " (grainflow theory: docs/MODELS.md, \"Kinetic theory of a vibrated bed\")");
  };
  const bool edmd = c.engine.kind == "edmd";
  if (edmd && c.engine.dimension != 3)
    fail("engine.dimension", "the kinetic theory is for spheres: dimension must be 3");
  int moving = 0;
  for (const auto& s : c.species) {
    if (s.frozen)
      fail("species.frozen", "species '" + s.name + "' is frozen: the theory has no fixed particles in the bed");
    ++moving;
  }
  if (moving != 1) fail("species", "the theory is for one species of identical spheres, not " + std::to_string(moving));

  const dem::DerivedQuantities d = dem::derive(c);
  const int axis = d.gravity_axis;
  const double g = d.gravity_magnitude;
  if (!(g > 0.0)) fail("gravity.vector", "the theory needs gravity: the floor carries the bed's weight");
  for (int a = 0; a < 3; ++a)
    if (a != axis && std::fabs(c.gravity[a]) > 1e-12 * g)
      fail("gravity.vector", "gravity must point along one axis, normal to the floor");
  const int floor = axis * 2 + (c.gravity[axis] < 0.0 ? 0 : 1);
  const std::string floor_name = kFaceNames[floor];
  if (c.domain.faces[floor] == FaceKind::bumpy)
    fail("domain.boundary", "the floor (" + floor_name + ") is bumpy; the theory's floor is a flat plane");
  if (c.domain.faces[floor] != FaceKind::wall)
    fail("domain.boundary", "the face gravity points at (" + floor_name + ") must be a wall: the theory's floor");
  if (!c.drive.enabled)
    fail("drive",
         "the theory needs a [drive] on the floor (" + floor_name + "): a still floor gives the bed no energy");
  if (c.drive.face != floor)
    fail("drive.face", std::string("the driven face is ") + (c.drive.face >= 0 ? kFaceNames[c.drive.face] : "none") + ", not the floor (" +
                           floor_name + ") that gravity points at");
  const double amplitude = c.drive.amplitude[axis], frequency = c.drive.frequency[axis];
  const double speed = 2.0 * M_PI * frequency * amplitude;
  if (!(speed > 0.0))
    fail("drive.amplitude",
         "the floor does not move along gravity: a smooth bed gets no energy from a floor sliding in its own plane");

  TheoryInputs in;
  const SpeciesConfig& s = c.species[d.reference_species];
  in.diameter = s.diameter;
  in.density = s.density;
  in.gravity = g;
  in.boundary_fluctuation_velocity = d.boundary_fluctuation_velocity;
  in.shaking_acceleration = d.shaking_acceleration;
  in.floor_amplitude = std::fabs(amplitude);
  in.domain_height = c.domain.length(axis);
  auto& p = in.parameters;
  p.mass_holdup = d.mass_holdup;
  // Only the floor's velocity along its normal reaches smooth spheres: <u^2> = (2 pi f a)^2 / 2.
  p.floor_variance = 0.5 * speed * speed / (g * s.diameter);

  const WallConfig& w = c.walls[floor];
  if (edmd) {
    if (restitution_law_named(c.collision.restitution_law) != RestitutionLawKind::constant)
      fail("collision.restitution_law",
           "the theory needs a constant restitution coefficient, not the '" + c.collision.restitution_law + "' law");
    p.restitution = c.collision.restitution;
    p.floor_restitution = w.restitution >= 0.0 ? w.restitution : c.collision.wall_restitution;
    if (c.collision.tangential_restitution != -1.0 || wall_condition_named(w.condition) != WallCondition::smooth)
      in.notes.push_back("rough collisions (collision.tangential_restitution or a rough floor) are treated as smooth");
  } else {
    // The contact law's closed forms: a head-on pair of reference spheres, and one against the
    // immovable floor.
    dem::visit_contact_law(c.contact.model, [&]<dem::ContactLaw Law>() {
      const typename Law::Params pair = Law::pair_params(c.contact, s);
      p.restitution =
          Law::binary_contact(pair, {0.5 * d.reference_mass, 0.25 * s.diameter, d.impact_speed}).restitution;
      p.floor_restitution = Law::binary_contact(Law::wall_params(pair, w.contact, 0.0),
                                                {s.mass(c.engine.dimension), 0.5 * s.diameter, d.impact_speed})
                                .restitution;
    });
  }
  if (!edmd && (c.contact.friction > 0.0 || w.friction > 0.0))
    in.notes.push_back("friction is ignored: the theory is for smooth spheres");
  for (int a = 0; a < 3; ++a)
    if (a != axis && c.drive.amplitude[a] != 0.0 && c.drive.frequency[a] != 0.0) {
      in.notes.push_back(
          "the floor's motion in its own plane is left out: it does not reach smooth spheres on a flat floor");
      break;
    }
  if (in.floor_amplitude > 0.5 * s.diameter)
    in.notes.push_back(
        fmt::format("the floor's amplitude ({:.3g} d) is not small: the theory's floor model neglects the "
                    "floor's displacement and keeps only its velocity",
                    in.floor_amplitude / s.diameter));
  if (d.shaking_acceleration < 10.0)
    in.notes.push_back(
        fmt::format("Gamma = {:.3g}: Lan 1994 (section 4.1.4) found the theory matching simulations at "
                    "Gamma = 28 and 57 but not at 5.7 and below, where the bed is not thermalised",
                    d.shaking_acceleration));
  return in;
}

namespace {

struct RunCase {
  std::string path;
  std::vector<std::string> overrides;  // the run's own --set assignments (a sweep's point)
};

// The case named by a run folder's summary.json, with the assignments the run applied to it.
RunCase case_of_run(const fs::path& dir) {
  const fs::path summary = dir / "summary.json";
  if (!fs::exists(summary))
    throw InputError(dir.string(), "",
                     "not a run's output folder: it has no summary.json (give a case file or a run's folder)");
  std::ifstream in(summary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(summary.string(), "", "cannot read the file");
  io::FlatJsonFields fields;
  try {
    fields = io::read_flat_json(text.str());
  } catch (const io::JsonParseError& e) {
    throw InputError(summary.string(), "", e.what());
  }
  RunCase run;
  for (const auto& [key, value] : fields)
    if (key == "case_overrides" && value.kind == io::FlatJsonValue::Kind::string)
      run.overrides = split_overrides(value.text);
  for (const auto& [key, value] : fields) {
    if (key != "case") continue;
    if (value.kind != io::FlatJsonValue::Kind::string || value.text.empty())
      throw InputError(summary.string(), "case", "must be the path of the run's case file");
    if (!fs::exists(value.text))
      throw InputError(summary.string(), "case",
                       "names '" + value.text +
                           "', which does not exist here (the path is as given to grainflow run; "
                           "run grainflow theory from the same folder, or give the case file itself)");
    run.path = value.text;
    return run;
  }
  throw InputError(summary.string(), "case", "missing: the run's case file is not recorded");
}

}  // namespace

int run_theory(const TheoryOptions& options) {
  const fs::path input(options.input);
  std::string case_path = options.input;
  fs::path output = options.output;
  std::vector<std::string> overrides = options.overrides;
  if (fs::is_directory(input)) {
    RunCase run = case_of_run(input);
    case_path = run.path;
    // The run's own assignments first, so that the command line's --set still wins.
    overrides.insert(overrides.begin(), run.overrides.begin(), run.overrides.end());
    if (output.empty()) output = input / "analysis" / "kinetic_theory.csv";
  } else if (!fs::exists(input)) {
    throw InputError(options.input, "", "no such case file or run folder");
  }
  if (output.empty()) output = "kinetic_theory.csv";

  const CaseConfig c = load_case(case_path, overrides);
  TheoryInputs in = theory_inputs(c);
  if (options.contact_value == "carnahan_starling")
    in.parameters.contact_value = analysis::ContactValueModel::carnahan_starling;
  else if (options.contact_value != "torquato")
    throw InputError("--g0", "", "must be torquato or carnahan_starling, not '" + options.contact_value + "'");

  analysis::KineticTheoryProfile r;
  try {
    r = analysis::solve_vibrated_bed(in.parameters);
  } catch (const std::invalid_argument& e) {
    throw InputError(c.path, "", e.what());
  } catch (const analysis::KineticTheoryError& e) {
    throw RunError(std::string(e.what()) + " (case " + c.path + ")");
  }

  const auto& p = in.parameters;
  const double d = in.diameter, g = in.gravity, rho = in.density;
  const double temperature_scale = g * d, pressure_scale = rho * g * d, flux_scale = rho * std::pow(g * d, 1.5);
  if (!output.parent_path().empty()) fs::create_directories(output.parent_path());
  io::write_atomically(output.string(), [&](std::ostream& out) {
    out << "# kinetic theory of a vibrated bed (docs/MODELS.md): smooth inelastic spheres, Lun et al. 1984 "
           "conductivity, g0 "
        << options.contact_value << ", flat floor vibrating along gravity (impact model, momentum-consistent rate);"
        << " case " << c.path << "; d = " << d << " m, rho_s = " << rho << " kg/m^3, g = " << g
        << " m/s^2, e = " << p.restitution << ", e_w = " << p.floor_restitution << ", m_t = " << p.mass_holdup
        << ", V_b = " << in.boundary_fluctuation_velocity << ", <u^2>/(g d) = " << p.floor_variance
        << ", Gamma = " << in.shaking_acceleration << "\n";
    out << "# units: Y = y/d above the floor, solids_fraction 1, W = sqrt(T/(g d)) 1, temperature T m^2/s^2, "
           "pressure Pa, heat_flux W/m^2 (upward)\n";
    out << "Y,solids_fraction,W,temperature,pressure,heat_flux\n" << std::setprecision(10);
    for (std::size_t i = 0; i < r.Y.size(); ++i)
      out << r.Y[i] << ',' << r.solids_fraction[i] << ',' << r.W[i] << ',' << r.temperature[i] * temperature_scale
          << ',' << r.pressure[i] * pressure_scale << ',' << r.heat_flux[i] * flux_scale << '\n';
  });

  // Peak solids fraction and the height below which 99.9% of the mass lies.
  std::size_t peak = 0;
  double mass = 0.0, top = r.Y.back();
  for (std::size_t i = 0; i < r.Y.size(); ++i) {
    if (r.solids_fraction[i] > r.solids_fraction[peak]) peak = i;
    if (i > 0) {
      mass += 0.5 * (r.Y[i] - r.Y[i - 1]) * (r.solids_fraction[i] + r.solids_fraction[i - 1]);
      if (mass >= 0.999 * p.mass_holdup && top == r.Y.back()) top = r.Y[i];
    }
  }
  std::cout << fmt::format(
      "kinetic theory: m_t = {:.4g}, V_b = {:.4g} (<u^2>/(g d) = {:.4g}), e = {:.4g}, e_w = {:.4g}\n", p.mass_holdup,
      in.boundary_fluctuation_velocity, p.floor_variance, p.restitution, p.floor_restitution);
  std::cout << fmt::format(
      "  W(0) = {:.4g}, nu(0) = {:.4g}, peak nu = {:.4g} at Y = {:.4g}, 99.9% of the mass below Y = {:.4g}\n",
      r.W.front(), r.solids_fraction.front(), r.solids_fraction[peak], r.Y[peak], top);
  std::cout << "  (written to " << output.string() << ")\n";
  for (const auto& note : in.notes) std::cerr << "grainflow: note: " << note << "\n";
  for (const auto& warning : r.warnings) std::cerr << "grainflow: warning: " << warning << "\n";
  if (top * d > in.domain_height)
    std::cerr << fmt::format(
        "grainflow: warning: the theory's bed reaches Y = {:.4g}, above the case's domain ({:.4g} d)\n", top,
        in.domain_height / d);
  return 0;
}

}  // namespace grainflow::run
