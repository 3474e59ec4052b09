// coarse_grained.vti of a soft-sphere run ([coarse_grain]): density, solid fraction, momentum,
// velocity and the kinetic, contact and total stress tensors on a 3D grid of cells over the box,
// coarse-grained with a Gaussian or Lucy kernel (observe/coarse_grain_field.hpp) and averaged over
// samples every coarse_grain.interval from coarse_grain.start. Each MPI rank adds its particles and
// the contacts it lists; the sums are added over the ranks when written.
#pragma once

#include "grainflow/observe/coarse_grain_field.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/step_schedule.hpp"

namespace grainflow::observe {

class CoarseGrainObserver final : public Observer {
 public:
  CoarseGrainObserver(const RunContext& run, const Frame& start);

  std::string name() const override { return "coarse_grain"; }
  void sample(const Frame& now) override;
  bool reads_contact_forces_at(long step) const override { return schedule_.due_at(step); }
  void serialize(io::StateArchive& ar) override { ar(field_, schedule_, first_, last_); }
  void save_portable(io::StateArchive& ar) override {
    CoarseGrainField whole = field_;
    whole.sum_over_ranks(run_.ranks);
    ar(whole, schedule_, first_, last_);
  }
  void load_portable(io::StateArchive& ar, bool keeper) override {
    serialize(ar);
    if (!keeper) field_.clear_sums();
  }
  void write(const Frame& last, OutputSink& out) override;

  const CoarseGrainField& field() const { return field_; }

 private:
  RunContext run_;
  CoarseGrainField field_;
  Schedule schedule_;
  double start_ = 0.0;                 // s, the first sample at or after it
  double first_ = -1.0, last_ = -1.0;  // s, the first and last sample taken
};

}  // namespace grainflow::observe
