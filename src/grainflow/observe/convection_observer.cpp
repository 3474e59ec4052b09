#include "grainflow/observe/convection_observer.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/config/case_checks.hpp"
#include "grainflow/config/toml_reader.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/observe/floor_motion.hpp"
#include "grainflow/observe/zone_profile_observer.hpp"

namespace grainflow::observe {
namespace {

constexpr long long kDefaultPhaseBins = 8;

void read_table(TomlReader& r, const CaseConfig&, ObserverParameters& out) {
  const std::string axis = r.string("axis", "z");
  if (axis != "x" && axis != "y" && axis != "z") r.fail("axis", "must be \"x\", \"y\" or \"z\"");
  out.set_text("axis", axis);
  const double cell = r.number("cell", 0.0);
  if (cell < 0.0) r.fail("cell", "must not be negative (0 = one diameter)");
  out.set_number("cell", cell);
  const double start = r.number("start", -1.0);
  if (r.has("start") && start < 0.0) r.fail("start", "must not be negative");
  if (r.has("start")) out.set_number("start", start);
  const double interval = r.number("interval", 0.0);
  if (interval < 0.0) r.fail("interval", "must not be negative (0 = every time step)");
  out.set_number("interval", interval);
  const long long bins = r.integer("phase_bins", kDefaultPhaseBins);
  if (bins < 0 || bins > 360) r.fail("phase_bins", "must lie in [0, 360] (0 = no phase-binned fields)");
  out.set_integer("phase_bins", bins);
}

// The table's horizontal axis as an index (0 = x).
int horizontal_axis(const ObserverParameters& table) { return table.text("axis")[0] - 'x'; }

void check_table(const ObserverParameters& table, const ObserverCheckInputs& run) {
  const CaseConfig& c = run.c;
  if (horizontal_axis(table) == run.gravity_axis)
    case_checks::fail(c, "field.axis", "must be a horizontal axis; it is the gravity axis");
  const double cell = table.number("cell");
  if (cell > 0.0 && cell < 0.1 * run.reference_diameter)
    case_checks::fail(c, "field.cell", "is under a tenth of a diameter: most cells would stay empty");
  const double f = c.drive.enabled ? c.drive.frequency[run.gravity_axis] : 0.0;
  if (table.integer("phase_bins") > 0 && !(f > 0.0))
    case_checks::fail(c, "field.phase_bins",
                      "needs a drive along gravity (set phase_bins = 0 for the long-term field only)");
  const double interval = table.number("interval");
  if (interval > 0.0 && interval < run.time_step)
    case_checks::fail(c, "field.interval", "is shorter than one time step");
}

// The case's [field], as read_table stored it.
const ObserverParameters& table_of(const RunContext& run) {
  return run.c->observer_tables.at(ConvectionObserver::table.table);
}

VelocityField make_field(const RunContext& run, const ObserverParameters& table) {
  const CaseConfig& c = *run.c;
  const int horizontal = horizontal_axis(table);
  const int axis = run.gravity_axis;
  const double cell = table.number("cell") > 0.0 ? table.number("cell") : run.reference_diameter;
  return VelocityField(horizontal, axis, c.domain.lo[horizontal], c.domain.hi[horizontal], ZoneLayout(run).lo,
                       c.domain.hi[axis], cell, static_cast<int>(table.integer("phase_bins")));
}

}  // namespace

const ObserverSchema ConvectionObserver::table = {
    "field", "dem", "velocity fields are implemented for the DEM engine only", &read_table, &check_table};

ConvectionObserver::ConvectionObserver(const RunContext& run)
    : run_(run),
      field_(make_field(run, table_of(run))),
      start_(table_of(run).has("start") ? table_of(run).number("start") : run.c->output.average_start),
      interval_(table_of(run).number("interval")) {}

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
  const ObserverParameters& t = table_of(run_);
  const double cell = t.number("cell") > 0.0 ? t.number("cell") : field_.cell();
  auto header = [&](std::ostream& file, const std::string& what) {
    file << "# " << what << ": horizontal axis " << names[horizontal_axis(t)] << ", vertical axis "
         << names[run_.gravity_axis] << ", cell " << cell << " m, " << field_.samples()
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
      header(
          file,
          "convection field in " + std::to_string(field_.bins()) +
              " bins of the floor phase omega (t - drive.start) + phase (0: floor at rest height moving up fastest)");
      file << "phase_bin,column,row,horizontal,vertical,visits,velocity_horizontal,velocity_vertical,speed\n";
      for (int b = 0; b < field_.bins(); ++b) cells(file, b);
    });
  out.summary->number("convection_speed", field_.convection_speed());
  out.summary->number("convection_speed_cell_mean", field_.cell_mean_convection_speed());
  out.summary->number("convection_speed_cell_mean_dense", field_.cell_mean_convection_speed(kDenseCellFraction));
}

}  // namespace grainflow::observe
