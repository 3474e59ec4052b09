#include "grainflow/run/run_session.hpp"

#include <filesystem>
#include <utility>

#include "grainflow/config/case_writer.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/run/run_records.hpp"

namespace grainflow::run {
namespace {

// An engine's session with the run's records around it, as run_with_records keeps them for
// `grainflow run`: the resolved case before the first step, the log when the outputs are written.
class RecordedSession final : public RunSession {
 public:
  RecordedSession(const CaseConfig& c, const RunOptions& options, std::vector<std::string> command_line)
      : case_(c), options_(options), command_line_(std::move(command_line)) {
    const bool existed = std::filesystem::exists(options.output_directory);
    try {
      engine_ = c.engine.kind == "edmd" ? open_edmd_session(case_, options_) : open_dem_session(case_, options_);
    } catch (const InputError&) {
      std::error_code ignored;
      if (!existed) std::filesystem::remove_all(options.output_directory, ignored);
      throw;
    }
    io::write_atomically(options_.output_directory + "/resolved_case.toml",
                         [&](std::ostream& out) { out << write_case_toml(case_); });
    start_ = wall_clock::now();
  }
  bool event_driven() const override { return engine_->event_driven(); }
  int dimension() const override { return engine_->dimension(); }
  double time() override { return engine_->time(); }
  long long steps() override { return engine_->steps(); }
  double time_step() const override { return engine_->time_step(); }
  double end_time() const override { return engine_->end_time(); }
  long long last_step() const override { return engine_->last_step(); }
  void advance_steps(long long n) override { logged([&] { engine_->advance_steps(n); }); }
  void advance_time(double dt) override { logged([&] { engine_->advance_time(dt); }); }
  int take_interrupt() override { return engine_->take_interrupt(); }
  int run() override {
    int status = 1;
    logged([&] { status = engine_->run(); });
    return status;
  }
  int finish() override {
    int status = 1;
    logged([&] { status = engine_->finish(); });
    return status;
  }
  bool finished() const override { return engine_->finished(); }
  ParticleStore& particles() override { return engine_->particles(); }
  void particles_written(bool positions) override { engine_->particles_written(positions); }
  std::vector<std::uint32_t> add_particles(const std::vector<int>& species, const std::vector<Vec3>& position,
                                           const std::vector<Vec3>& velocity) override {
    return engine_->add_particles(species, position, velocity);
  }
  void remove_particles(const std::vector<std::uint32_t>& ids) override { engine_->remove_particles(ids); }
  const std::string& output_directory() const override { return engine_->output_directory(); }

 private:
  // Calls `stage`; once the engine has written its outputs (the end, or a failure), the log.
  template <class Stage>
  void logged(Stage&& stage) {
    try {
      stage();
    } catch (const RunError&) {
      write_log(1);
      throw;
    }
    if (engine_->finished()) write_log(engine_->finish());
  }
  void write_log(int status) {
    if (std::exchange(logged_, true)) return;
    write_run_log(options_.output_directory, case_, options_, command_line_, start_, wall_clock::now(), status);
  }
  const CaseConfig case_;
  const RunOptions options_;
  const std::vector<std::string> command_line_;
  std::unique_ptr<RunSession> engine_;
  wall_clock::time_point start_;
  bool logged_ = false;
};

}  // namespace

std::unique_ptr<RunSession> open_session(const CaseConfig& c, const RunOptions& options,
                                         const std::vector<std::string>& command_line) {
  return std::make_unique<RecordedSession>(c, options, command_line);
}

}  // namespace grainflow::run
