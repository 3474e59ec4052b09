// A silo's orifice clogged by an arch: no particle out through the [[outlet]]s for run.clog_time
// (by default 50 sqrt(d / g) with an outlet: many times a grain's fall through its diameter). The
// run stops at the output time that sees it and says so in summary.json.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/io/json_writer.hpp"

namespace grainflow::run {

class ClogWatch {
 public:
  ClogWatch() = default;
  ClogWatch(const CaseConfig& c, double max_diameter) {
    if (c.outlets.empty() || c.run.clog_time == 0.0) return;
    const double g = norm(c.gravity);
    patience_ = c.run.clog_time > 0.0 ? c.run.clog_time : (g > 0.0 ? 50.0 * std::sqrt(max_diameter / g) : 0.0);
  }
  bool on() const { return patience_ > 0.0; }
  // `out`: the particles out so far (every rank's), at `time`.
  void update(double out, double time) {
    if (out > outflow_) outflow_ = out, last_ = time;
    else if (time - last_ >= patience_) clogged_at_ = time;
  }
  bool clogged() const { return clogged_at_.has_value(); }
  void report(io::JsonObject& summary, std::vector<std::string>& warnings) const {
    if (!on()) return;
    summary.boolean("clogged", clogged());
    if (!clogged()) return;
    summary.number("clogged_at", *clogged_at_);
    warnings.push_back("the outlets clogged: no particle left for " + std::to_string(patience_) + " s up to t = " +
                       std::to_string(*clogged_at_) + " s; the run stopped there (run.clog_time)");
  }

 private:
  double patience_ = 0.0;  // s
  double outflow_ = 0.0, last_ = 0.0;
  std::optional<double> clogged_at_;
};

}  // namespace grainflow::run
