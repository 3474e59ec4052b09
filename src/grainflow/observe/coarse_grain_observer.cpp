#include "grainflow/observe/coarse_grain_observer.hpp"

#include <cmath>
#include <string>

#include "grainflow/core/ball_measure.hpp"
#include "grainflow/io/vti_writer.hpp"

namespace grainflow::observe {
namespace {

CoarseGrainKernel kernel_of(const CoarseGrainConfig& g, double reference_diameter, int dimension) {
  CoarseGrainKernel k;
  k.dimension = dimension;
  k.kind = g.kernel == "lucy" ? CoarseGrainKernel::Kind::lucy : CoarseGrainKernel::Kind::gaussian;
  k.width = g.kernel_size(reference_diameter);
  return k;
}

double sample_interval(const CaseConfig& c) {
  if (c.coarse_grain.interval > 0.0) return c.coarse_grain.interval;
  return c.output.profile_interval > 0.0 ? c.output.profile_interval : c.output.interval / 10.0;
}

}  // namespace

CoarseGrainObserver::CoarseGrainObserver(const RunContext& run, const Frame& start)
    : run_(run),
      field_(*start.box, run.c->coarse_grain.grid(start.box->hi - start.box->lo, run.reference_diameter, run.dimension),
             kernel_of(run.c->coarse_grain, run.reference_diameter, run.dimension)),
      schedule_(sample_interval(*run.c), run.time_step),
      start_(run.c->coarse_grain.start >= 0.0 ? run.c->coarse_grain.start : run.c->output.average_start) {}

void CoarseGrainObserver::sample(const Frame& now) {
  if (!schedule_.due(now.step) || now.time < start_ - 0.5 * now.time_step) return;
  const ParticleStore& p = *now.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    field_.add_particle(p.position[i], p.mass[i], ball_measure(run_.dimension, p.radius[i]), p.velocity[i]);
  }
  now.contact_forces([&](std::uint32_t i, int, const Vec3& from, const Vec3& force) {
    field_.add_contact(p.position[i], from, force);
  });
  field_.close_sample();
  if (first_ < 0.0) first_ = now.time;
  last_ = now.time;
}

void CoarseGrainObserver::write(const Frame&, OutputSink& out) {
  CoarseGrainField whole = field_;
  whole.sum_over_ranks(run_.ranks);
  if (whole.samples() == 0)
    out.warnings->push_back("coarse_grained.vti: no sample after coarse_grain.start; its fields are zero");
  if (whole.lost_mass() > 0.0 && whole.samples() > 0)
    out.warnings->push_back("coarse_grained.vti: " + std::to_string(whole.lost_mass() / whole.samples()) +
                            " kg per sample lay beyond the grid's reach (outside the box) and is not in the fields");
  if (out.summary) {
    out.summary->integer("coarse_grain_samples", whole.samples());
    out.summary->integer("coarse_grain_cells", static_cast<long long>(whole.cell_count()));
  }
  if (!out.writes) return;
  const std::size_t n = whole.cell_count();
  io::CellArray density{"density", 1, {}}, solid{"solid_fraction", 1, {}}, momentum{"momentum_density", 3, {}},
      velocity{"velocity", 3, {}}, kinetic{"kinetic_stress", 9, {}}, contact{"contact_stress", 9, {}},
      total{"total_stress", 9, {}};
  for (std::size_t k = 0; k < n; ++k) {
    const CoarseGrainCell cell = coarse_grain_cell(whole, k);
    density.values.push_back(cell.density);
    solid.values.push_back(cell.solid_fraction);
    for (int a = 0; a < 3; ++a) momentum.values.push_back(cell.momentum[a]);
    for (int a = 0; a < 3; ++a) velocity.values.push_back(cell.velocity[a]);
    kinetic.values.insert(kinetic.values.end(), cell.kinetic.begin(), cell.kinetic.end());
    contact.values.insert(contact.values.end(), cell.contact.begin(), cell.contact.end());
    total.values.insert(total.values.end(), cell.total.begin(), cell.total.end());
  }
  io::write_vti(out.directory + "/coarse_grained.vti", io::ImageGrid{whole.cells(), whole.origin(), whole.spacing()},
                {density, solid, velocity, momentum, total, contact, kinetic},
                {{"samples", static_cast<double>(whole.samples())},
                 {"first_sample_time", first_},
                 {"last_sample_time", last_},
                 {std::string("kernel_") + (whole.kernel().kind == CoarseGrainKernel::Kind::lucy ? "cutoff" : "width"),
                  whole.kernel().width},
                 {"kernel_standard_deviation", whole.kernel().standard_deviation()}});
}

}  // namespace grainflow::observe
