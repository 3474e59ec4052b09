#include "grainflow/observe/convection_observer.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/io/atomic_file.hpp"
#include "grainflow/observe/floor_motion.hpp"
#include "grainflow/observe/zone_profile_observer.hpp"

namespace grainflow::observe {
namespace {

VelocityField make_field(const RunContext& run) {
  const CaseConfig& c = *run.c;
  const auto& f = c.field;
  const int axis = run.gravity_axis;
  const double cell = f.cell > 0.0 ? f.cell : run.reference_diameter;
  return VelocityField(f.axis, axis, c.domain.lo[f.axis], c.domain.hi[f.axis], ZoneLayout(run).lo, c.domain.hi[axis], cell,
                       f.phase_bins);
}

}  // namespace

ConvectionObserver::ConvectionObserver(const RunContext& run)
    : run_(run),
      field_(make_field(run)),
      start_(run.c->field.start >= 0.0 ? run.c->field.start : run.c->output.average_start),
      interval_(run.c->field.interval) {}

void ConvectionObserver::sample(const Frame& now) {
  if (now.time < start_ - 0.5 * now.time_step) return;
  if (interval_ > 0.0) {
    if (now.time < start_ + next_ * interval_ - 0.5 * now.time_step) return;
    ++next_;
  }
  int bin = -1;
  if (field_.bins() > 0) {
    const double phase = floor_phase(*run_.c, run_.gravity_axis, now.time);
    if (phase >= 0.0) bin = std::min(field_.bins() - 1, static_cast<int>(phase / (2.0 * M_PI) * field_.bins()));
  }
  field_.sample(*now.particles, bin);
}

void ConvectionObserver::write(const Frame& last, OutputSink& out) {
  (void)last;
  if (several_ranks()) field_.sum_over_ranks(run_.ranks);  // collective
  if (!out.writes) return;
  const CaseConfig& c = *run_.c;
  const char* names = "xyz";
  const double cell = c.field.cell > 0.0 ? c.field.cell : field_.cell();
  auto header = [&](std::ostream& file, const std::string& what) {
    file << "# " << what << ": horizontal axis " << names[c.field.axis] << ", vertical axis " << names[run_.gravity_axis]
         << ", cell " << cell << " m, " << field_.samples()
         << " samples; a particle's velocity counts toward the cell holding its centre (Lan 1994 Fig. 5.1)\n";
    file << "# units: horizontal, vertical m (cell centres), velocities m/s; visits = particle centres counted\n";
  };
  auto cells = [&](std::ostream& file, int bin) {
    for (const auto& k : field_.cells(bin)) {
      if (bin >= 0) file << bin << ',';
      file << k.column << ',' << k.row << ',' << k.horizontal << ',' << k.vertical << ',' << k.visits << ','
           << k.velocity_horizontal << ',' << k.velocity_vertical << ',' << k.speed() << '\n';
    }
  };
  io::write_atomically(out.directory + "/convection.csv", [&](std::ostream& file) {
    header(file, "long-term convection field");
    file << "column,row,horizontal,vertical,visits,velocity_horizontal,velocity_vertical,speed\n";
    cells(file, -1);
  });
  if (field_.bins() > 0)
    io::write_atomically(out.directory + "/convection_phases.csv", [&](std::ostream& file) {
      header(file, "convection field in " + std::to_string(field_.bins()) +
                       " bins of the floor phase omega (t - drive.start) + phase (0: floor at rest height moving up fastest)");
      file << "phase_bin,column,row,horizontal,vertical,visits,velocity_horizontal,velocity_vertical,speed\n";
      for (int b = 0; b < field_.bins(); ++b) cells(file, b);
    });
  out.summary->number("convection_speed", field_.convection_speed());
  out.summary->number("convection_speed_cell_mean", field_.cell_mean_convection_speed());
  out.summary->number("convection_speed_cell_mean_dense", field_.cell_mean_convection_speed(kDenseCellFraction));
}

}  // namespace grainflow::observe
