// convection.csv and convection_phases.csv of a soft-sphere run ([field], Lan 1994 Chapter 5):
// the long-term velocity field in cells of a vertical plane, and the same in bins of the floor's
// phase, with the mean convection speed (Table 5.1) in summary.json. The observer owns its table:
// its keys, their defaults and checks are its schema's, defined in its .cpp.
#pragma once

#include "grainflow/config/observer_schema.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/velocity_field.hpp"

namespace grainflow::observe {

// convection_speed_cell_mean_dense counts the cells visited at least this share of the mean.
inline constexpr double kDenseCellFraction = 0.1;

class ConvectionObserver final : public Observer {
 public:
  // [field]: axis (the plane's horizontal axis, "x", "y" or "z"; default "z", Lan's cell length),
  // cell (m, length and height; 0: the reference diameter), start (s; absent: output.average_start),
  // interval (s between samples; 0: every step, Lan's method), phase_bins (bins of the floor's
  // cycle, default 8; 0: none), each stored as read.
  static const ObserverSchema table;

  explicit ConvectionObserver(const RunContext& run);

  std::string name() const override { return "field"; }
  void sample(const Frame& now) override;
  void serialize(io::StateArchive& ar) override { ar(field_, next_); }
  void save_portable(io::StateArchive& ar) override {
    VelocityField whole = field_;
    if (several_ranks()) whole.sum_over_ranks(run_.ranks);
    ar(whole, next_);
  }
  void load_portable(io::StateArchive& ar, bool keeper) override {
    serialize(ar);
    if (!keeper) field_.clear_sums();
  }
  void write(const Frame& last, OutputSink& out) override;

 private:
  bool several_ranks() const { return run_.comm != nullptr && run_.comm->size() > 1; }

  RunContext run_;
  VelocityField field_;
  double start_ = 0.0, interval_ = 0.0;
  long next_ = 0;
};

}  // namespace grainflow::observe
