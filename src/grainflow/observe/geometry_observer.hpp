// geometry.csv of a soft-sphere run with [[geometry]] walls: at each output time (output.interval,
// the time series' times) the force and the torque about its motion origin that the particles exert
// on each geometry wall, summed over MPI ranks. Reads the loads through Frame::geometry_loads.
#pragma once

#include <string>
#include <vector>

#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/step_schedule.hpp"

namespace grainflow::observe {

class GeometryObserver final : public Observer {
 public:
  explicit GeometryObserver(const RunContext& run);

  std::string name() const override { return "geometry"; }
  void sample_start(const Frame& now) override { take(now); }
  void sample(const Frame& now) override {
    if (schedule_.due(now.step)) take(now);
  }
  // Every rank holds the sums (the ranks reduce at each sample): the portable form is the same.
  void serialize(io::StateArchive& ar) override { ar(schedule_, names_, values_); }
  void flush(OutputSink& out) override { write_file(out); }
  void write(const Frame& last, OutputSink& out) override {
    (void)last;
    write_file(out);
  }

  // Per sample: time, then per geometry force x y z, torque x y z.
  const std::vector<double>& values() const { return values_; }

 private:
  void take(const Frame& now);
  void write_file(const OutputSink& out) const;

  RankReduce ranks_;
  Schedule schedule_;
  std::vector<std::string> names_;
  std::vector<double> values_;
};

}  // namespace grainflow::observe
