// tracers.csv of a soft-sphere run ([tracers], Lan 1994 section 5.2): rows of time, id, unwrapped
// position, velocity, coordination (particles and walls touched) and the floor's motion, for the
// particles and species the case names; within a time, by id.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"

namespace grainflow::observe {

class TracerObserver final : public Observer {
 public:
  // `everyone`: every particle of the run (the species to follow are found in it).
  TracerObserver(const RunContext& run, const ParticleStore& everyone);

  struct Row {
    long sample = 0;  // the sample's index: rows sort by it, then by id
    std::uint32_t id = 0;
    std::string text;
    template <class Archive>
    void serialize(Archive& ar) {
      ar(sample, id, text);
    }
  };

  std::string name() const override { return "tracers"; }
  void sample(const Frame& now) override;
  void serialize(io::StateArchive& ar) override { ar(next_, rows_); }
  void save_portable(io::StateArchive& ar) override {
    std::vector<Row> all = gathered_rows();
    ar(next_, all);
  }
  void load_portable(io::StateArchive& ar, bool keeper) override {
    serialize(ar);
    if (!keeper) rows_.clear();
  }
  void flush(OutputSink& out) override { write_rows(out); }
  void write(const Frame&, OutputSink& out) override { write_rows(out); }

  // Collective: every rank's rows in order, on rank 0 (the others get none).
  std::vector<Row> gathered_rows() const;
  const std::vector<std::uint32_t>& ids() const { return ids_; }

 private:
  void write_rows(const OutputSink& out) const;  // collective: rank 0 gathers and writes

  RunContext run_;
  std::vector<std::uint32_t> ids_;  // sorted
  double start_ = 0.0, interval_ = 0.0;
  long next_ = 0;
  std::vector<Row> rows_;  // this rank's (MPI: the particles it owned at each sample)
};

}  // namespace grainflow::observe
