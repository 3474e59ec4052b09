// discharge.csv of a run with [[outlet]]s: at each output time (output.interval) the particles and
// the mass each outlet has removed so far, summed over MPI ranks; and in summary.json the steady
// discharge rate (mass per time, all outlets) with its error, over a window it reports, and the
// bulk solids fraction in the bed box an outlet names (Beverloo's C goes with that density).
#pragma once

#include <string>
#include <vector>

#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/step_schedule.hpp"

namespace grainflow::observe {

// The steady discharge rate of a cumulative mass M(t): the slope of M over the window between the
// times when 20 % and 80 % of the last sample's mass had left (a silo's start-up and its last,
// slowing part left out; a silo fed back by its outlet is steady throughout), and its error from
// the rates of 8 consecutive blocks of that window (their standard deviation over sqrt(8): each
// block's discharge is nearly independent of the next's).
struct DischargeRate {
  double rate = 0.0, error = 0.0;  // kg/s (kg/(m s) for discs)
  double start = 0.0, end = 0.0;   // s, the window
  bool measured = false;           // enough samples and mass
};
DischargeRate steady_discharge_rate(const std::vector<double>& time, const std::vector<double>& mass);

class DischargeObserver final : public Observer {
 public:
  explicit DischargeObserver(const RunContext& run);

  std::string name() const override { return "discharge"; }
  void sample_start(const Frame& now) override { take(now); }
  void sample(const Frame& now) override {
    if (schedule_.due(now.step)) take(now);
  }
  void serialize(io::StateArchive& ar) override { ar(schedule_, values_, bed_fraction_); }
  void flush(OutputSink& out) override { write_file(out); }
  void write(const Frame& last, OutputSink& out) override;

 private:
  void take(const Frame& now);
  void write_file(const OutputSink& out) const;

  RankReduce ranks_;
  Schedule schedule_;
  std::vector<std::string> names_;
  std::vector<double> values_;  // per sample: time, then per outlet removed and mass
  // The first outlet's bed box (bed_lo, bed_hi), if given, and its solids fraction per sample.
  bool has_bed_ = false;
  Vec3 bed_lo_, bed_hi_;
  int dimension_ = 3;
  std::vector<double> bed_fraction_;
};

}  // namespace grainflow::observe
