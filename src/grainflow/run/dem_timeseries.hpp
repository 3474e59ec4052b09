// A soft-sphere run's time series (timeseries.csv), one row per output interval, and the means with
// block-averaged error bars the summary takes from it.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "grainflow/analysis/block_average.hpp"
#include "grainflow/config/couette_servo_rule.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/observe/bed_surface.hpp"
#include "grainflow/engine_api/energy_budget.hpp"
#include "grainflow/observe/global_sample.hpp"

namespace grainflow::run {

struct TimeseriesRow {
  double time;
  observe::GlobalSample global;
  double floor_position, floor_velocity, max_overlap_ratio;
  long contacts, wall_contacts, rebuilds;
  observe::BedSurface bed;
  double zone_temperature;  // eq. (3-1-9)'s zone temperatures, about each zone's instantaneous mean, over the bed
  long collisions, wall_collisions;  // contacts begun since the start
  engine_api::EnergyBudget budget;   // since the start, over all ranks
  double budget_residual;
  CouetteServoState servo;  // the Couette servo's gap and last update, when it runs
};

void write_timeseries(const std::string& path, const std::vector<TimeseriesRow>& rows, bool servo);

// Mean and block-averaged standard error of a time-series column over the rows from `from` on.
struct MeanWithError {
  double mean = 0.0, error = NAN;
  long rows = 0;
};
template <class Get>
MeanWithError series_mean(const std::vector<TimeseriesRow>& rows, double from, Get&& get) {
  std::vector<double> x;
  for (const auto& r : rows)
    if (r.time >= from - 1e-12) x.push_back(get(r));
  MeanWithError m;
  m.rows = static_cast<long>(x.size());
  if (x.empty()) return m;
  if (x.size() < 32) {  // too short to block: the mean alone
    for (double v : x) m.mean += v / x.size();
    return m;
  }
  const auto b = analysis::block_average(x);
  m.mean = b.mean;
  m.error = b.standard_error;
  return m;
}

// `key` and, when the series was long enough to block, `key_error`.
void put(io::JsonObject& summary, const std::string& key, const MeanWithError& m);

}  // namespace grainflow::run
