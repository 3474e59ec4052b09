#include "grainflow/run/case_validation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "grainflow/config/case_checks.hpp"
#include "grainflow/core/periodic_box.hpp"
#include "grainflow/dem/dem_case_checks.hpp"
#include "grainflow/dem/neighbor_list.hpp"
#include "grainflow/edmd/edmd_case_checks.hpp"
#include "grainflow/particles/particle_store.hpp"
#include "grainflow/run/observer_registry.hpp"

namespace grainflow {
namespace {

using case_checks::fail;
using case_checks::fmt_number;

// Positions carry about 16 digits: beyond 1e9 diameters across, a contact's overlap (1e-3 d and
// less) would be lost in their rounding.
constexpr double kMaxDomainDiameters = 1e9;

void validate_extent(const CaseConfig& c) {
  double max_diameter = 0.0;
  for (const auto& s : c.species) max_diameter = std::max(max_diameter, s.diameter);
  if (!(max_diameter > 0.0)) return;  // the engines' checks name the species
  for (int axis = 0; axis < 3; ++axis) {
    const double diameters = c.domain.length(axis) / max_diameter;
    if (diameters > kMaxDomainDiameters)
      fail(c, "domain.hi",
           std::string("the domain is ") + fmt_number(diameters) + " diameters long along " + "xyz"[axis] +
               "; at most 1e9 (positions would lose the precision contacts need)");
  }
}

// Explicit hard particles (edmd, init = "file") must start apart: found with the soft-sphere
// engine's cell grid and pair list at zero skin.
void validate_hard_particles_apart(const CaseConfig& c) {
  const int dim = c.engine.dimension;
  double max_diameter = 0.0;
  for (const auto& s : c.species) max_diameter = std::max(max_diameter, s.diameter);
  for (const auto& record : c.initial_particles) max_diameter = std::max(max_diameter, record.diameter);
  // Explicit particles must not overlap: hard particles cannot start interpenetrating.
  ParticleStore p;
  p.resize(c.initial_particles.size());
  // Discs (2D) all lie in one plane: z is no axis to find images along.
  PeriodicBox box{
      c.domain.lo, c.domain.hi, {c.domain.periodic(0), c.domain.periodic(1), dim == 3 && c.domain.periodic(2)}};
  for (std::size_t i = 0; i < c.initial_particles.size(); ++i) {
    const auto& record = c.initial_particles[i];
    double d = record.diameter;
    for (const auto& s : c.species)
      if (d == 0.0 && s.name == record.species) d = s.diameter;
    p.position[i] = record.position;
    if (dim == 2) p.position[i].z = 0.5 * (c.domain.lo.z + c.domain.hi.z);
    p.target_radius[i] = p.radius[i] = 0.5 * d;
    p.id[i] = static_cast<std::uint32_t>(i);
    box.wrap(p.position[i], p.image[i]);
  }
  dem::CellGrid grid;
  grid.setup(box, max_diameter, p.size());
  grid.bin(p.position);
  dem::NeighborPairs pairs;
  grid.build_pairs(p, box, 0.0, 1, pairs);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (pairs.offsets[i + 1] > pairs.offsets[i])
      throw InputError(
          c.particles.file,
          "particles " + std::to_string(i + 1) + " and " + std::to_string(pairs.partner[pairs.offsets[i]] + 1),
          "overlap: hard particles must start apart");
}

// Each observer that owns its table checks it against the run.
void check_observer_tables(const ObserverCheckInputs& run) {
  for (const ObserverSchema& schema : run::observer_schemas())
    if (schema.check && run.c.observer_tables.has(schema.table))
      schema.check(run.c.observer_tables.at(schema.table), run);
}

}  // namespace

void validate_case(const CaseConfig& c) {
  validate_extent(c);
  if (c.engine.kind == "edmd") {
    edmd::validate_edmd_case(c);
    if (c.particles.init == "file") validate_hard_particles_apart(c);
    long particles = 0;
    for (const auto& s : c.species) particles += static_cast<long>(s.count);
    // No time step; the first species' diameter, and gravity along x or y as the event-driven run takes it.
    check_observer_tables(
        {c, 0.0, c.species.front().diameter, std::fabs(c.gravity.x) > std::fabs(c.gravity.y) ? 0 : 1, particles});
    return;
  }
  const dem::DerivedQuantities d = dem::validate_dem_case(c);
  const long particles = d.moving_particles + d.frozen_particles;
  check_observer_tables({c, d.time_step, d.reference_diameter, d.gravity_axis, particles});
}

}  // namespace grainflow
