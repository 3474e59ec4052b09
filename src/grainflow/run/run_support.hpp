// Pieces every engine's run driver shares: the exact time grid of outputs, the progress
// line, and final_state.csv.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/engine_api/energy_budget.hpp"
#include "grainflow/observe/step_schedule.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::run {

using observe::Schedule;

// The k-th time of a grid `interval` apart, k * interval, pulled back onto `end` when rounding puts it
// just past the end (3 * 0.1 > 0.3): an output due at the end of a run is taken, not lost.
inline double grid_time(long k, double interval, double end) {
  const double t = k * interval;
  return t > end && t - end <= 1e-9 * interval ? end : t;
}

// The progress line on stderr (simulated time, rate, ETA), when stderr is a terminal.
class Progress {
 public:
  Progress(bool enabled, double duration)
      : enabled_(enabled), duration_(duration), start_(clock::now()), last_(start_) {}
  void update(double time);
  void finish();

 private:
  using clock = std::chrono::steady_clock;
  bool enabled_;
  double duration_;
  clock::time_point start_, last_;
};

// A run's --set assignments for summary.json's "case_overrides": one per line, so that a run
// folder (e.g. one point of a sweep) names its exact case; split_overrides reads them back.
std::string join_overrides(const std::vector<std::string>& overrides);
std::vector<std::string> split_overrides(const std::string& joined);

// Adds errors and warnings to summary.json, writes it atomically into `dir`, and repeats the
// errors on stderr (unless `echo_errors` is false); returns `exit_status`.
int finish_summary(io::JsonObject& summary, const std::string& dir, const std::vector<std::string>& errors,
                   const std::vector<std::string>& warnings, int exit_status, bool echo_errors = true);

// summary.json's energy budget: energy_input (and its parts energy_input_gravity, _walls,
// _boundaries, _growth, _separation), energy_change, energy_dissipated, energy_budget_residual;
// `fallback_scale` as for EnergyBudget::residual.
void write_energy_budget(const engine_api::EnergyBudget& b, double fallback_scale, io::JsonObject& summary);

// final_state.csv: every particle by id, with exact doubles so the state can start another run.
void write_final_state(const std::string& path, const ParticleStore& p, const std::vector<SpeciesConfig>& species);

}  // namespace grainflow::run
