// An event-driven run's strip profiles (Campbell 1982 sections 3.1-3.2) and what an engineer reads
// from them: sampled every output.profile_interval from the start of the long-term averages, then
// written as profiles.csv with du/dy, Savage-Jeffrey's S and a plug-flow flag per strip, and the
// run's scalars in summary.json: for a chute (no top wall, gravity along the flow) the flow depth,
// mass flow, Froude number and Appendix A's profile parameters and critical Froude number, the
// slip at the bottom; for a Couette cell the slip at each wall and temperatures scaled by
// (H / U_T)^2. Also the convergence check of section 2.5 on the kinetic-energy history.
#pragma once

#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/observe/block_sums.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/strip_layout.hpp"
#include "grainflow/observe/strip_profile.hpp"

namespace grainflow::observe {

// One strip's long-term averages with the velocity gradient fitted across the strips.
struct StripKinematics {
  StripAverages averages;
  double du_dy = 0.0, du_dy_error = 0.0;  // 1/s
  bool plug_flow = false;
};

class StripProfileObserver final : public Observer {
 public:
  StripProfileObserver(const RunContext& run, const Frame& start);

  std::string name() const override { return "profiles"; }
  // The next sample time on the grid k * profile_interval.
  double next_time() const override { return next_ * interval_; }
  // At next_time(): samples the state (synchronized there) once the long-term averages have begun
  // (time > output.average_start and collisions >= output.average_start_collisions).
  void sample(const Frame& now) override;
  // The time of the first sample taken, or NaN.
  double first_sample_time() const override { return first_sample_; }

  // profiles.csv, and the scalars into the summary; the warnings get what the user should know.
  void write(const Frame& last, OutputSink& out) override;
  // The strips' averages as profiles.csv has them.
  std::vector<StripKinematics> strip_kinematics() const;
  long samples() const { return profile_.samples(); }

  void serialize(io::StateArchive& ar) override {
    ar(profile_, next_, first_sample_, sum_height_, sum_gap_, sum_bottom_speed_, sum_top_speed_, bulk_blocks_, bottom_,
       thickness_, cross_section_);
  }

 private:
  struct Derived;  // du/dy, S and plug flow per strip; chute and Couette scalars
  void derive_strips(const std::vector<StripAverages>& strips, Derived& d) const;
  void derive_couette(const std::vector<StripAverages>& strips, Derived& d) const;
  void derive_chute(const std::vector<StripAverages>& strips, Derived& d) const;

  const CaseConfig& c_;
  StripLayout strips_;
  StripProfile profile_;
  double interval_;
  long next_ = 1;
  double first_sample_;
  int bottom_wall_ = -1, top_wall_ = -1;
  bool chute_;
  // Sums over the samples: chute mass-mean height above the bottom; Couette gap and wall speeds.
  double sum_height_ = 0.0, sum_gap_ = 0.0, sum_bottom_speed_ = 0.0, sum_top_speed_ = 0.0;
  // The same per sample in blocks, for the chute scalars' standard errors.
  struct BulkSample {
    double height = 0.0, momentum = 0.0, mass = 0.0;  // m, kg m/s (x), kg
    BulkSample& operator+=(const BulkSample& o) {
      height += o.height, momentum += o.momentum, mass += o.mass;
      return *this;
    }
  };
  BlockSums<BulkSample> bulk_blocks_;
  // At the last sample: the strips' low end and thickness, m, and their cross-section, m (3D: m^2).
  double bottom_ = 0.0, thickness_ = 0.0, cross_section_ = 0.0;
};

}  // namespace grainflow::observe
