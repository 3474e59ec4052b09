// What the two engines' RunSessions share: a run driver (DemRun, EdmdRun) built over the case and
// options the session keeps, its clock and particles, and the rules for going on: not after the
// outputs are written, not past run.duration, the particles' new values taken up first, and a
// failure reported as RunError once the outputs (with it) are written.
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <variant>

#include "grainflow/core/error.hpp"
#include "grainflow/run/run_session.hpp"

namespace grainflow::run {

template <class Run>
class RunSessionOver : public RunSession {
 public:
  RunSessionOver(const CaseConfig& c, const RunOptions& o) : case_(c), options_(o), run_(case_, options_) {}

  int dimension() const override { return case_.engine.dimension; }
  double end_time() const override { return case_.run.duration; }
  double time() override { return std::visit([](auto& e) { return e.state().time; }, run_.engine_variant()); }
  int take_interrupt() override { return run_.take_interrupt(); }
  int run() override {
    refuse_when_finished();
    take_up_writes();
    return run_.run();
  }
  int finish() override { return run_.finish(); }
  bool finished() const override { return run_.finished(); }
  ParticleStore& particles() override {
    return std::visit([](auto& e) -> ParticleStore& { return e.state().particles; }, run_.engine_variant());
  }
  const std::string& output_directory() const override { return run_.output_directory(); }

 protected:
  // The engine's share of taking up values written into the particles (after `written_` was set).
  virtual void take_up_writes() = 0;

  void refuse_when_finished() const {
    if (run_.finished()) throw RunError("the run has finished: its outputs are written");
  }
  void refuse_negative(double amount, const char* what) const {
    if (!(amount >= 0.0))
      throw InputError(case_.path, "", std::string("a run advances by ") + what + " >= 0, not " + std::to_string(amount));
  }
  void refuse_beyond(bool beyond, const std::string& end, const std::string& target) const {
    if (beyond)
      throw InputError(case_.path, "run.duration",
                       "the run ends at " + end + ": it cannot advance to " + target + " (set a longer run.duration)");
  }
  // The driver's advance to `target`; a failure there is the session's RunError, outputs written.
  template <class Target>
  void advance_driver(Target target) {
    take_up_writes();
    if (run_.advance(target)) {
      run_.finish();
      throw RunError(run_.first_error());
    }
  }

  const CaseConfig case_;
  const RunOptions options_;
  Run run_;
  bool written_ = false;
};

}  // namespace grainflow::run
