// constitutive.csv of an event-driven run: Campbell's (1982) equation-of-state function chi(nu)
// (section 3.1.1) and Bagnold/Savage functions f_s(nu), f_N(nu) (section 3.3.1) strip by strip,
// from the strip profiles (solids fraction, velocity variances, du/dy) and the collision stresses
// (measured directly, and by the weight integral as Campbell did), with the equivalent 3D solids
// fraction and flags telling which strips a table over many runs should use.
// `grainflow constitutive` gathers these files into one table.
#pragma once

#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/observe/collision_stress.hpp"
#include "grainflow/observe/collision_stress_observer.hpp"
#include "grainflow/observe/strip_profile_observer.hpp"

namespace grainflow::observe {

// Which strips go into the table: not the strips whose particles touch a wall (a wall's impulses
// lie in them), not nearly empty ones, and, for f, not plugs and not where du/dy is so poorly
// resolved that f_N is uncertain by more than half its value ((du/dy)^2 doubles du/dy's relative
// error: this asks |du/dy| > 4 standard errors at least).
inline constexpr double kConstitutiveMinimumSolidsFraction = 0.02;
inline constexpr double kConstitutiveMaximumRelativeError = 0.5;

// `strips` and `stresses` come from the same strip grid (index k is the same strip in both).
// `wall_below` / `wall_above`: whether the first / last strip lies against a wall.
void write_constitutive(const std::string& path, const CaseConfig& c, int dimension,
                        const std::vector<StripKinematics>& strips, const std::vector<StripStress>& stresses,
                        bool wall_below, bool wall_above);

// constitutive.csv from the strip profiles and the collision stresses of the same run, once both
// are written (it samples nothing itself).
class ConstitutiveObserver final : public Observer {
 public:
  ConstitutiveObserver(const RunContext& run, const StripProfileObserver& profiles,
                       const CollisionStressObserver& stresses)
      : c_(run.c), profiles_(&profiles), stresses_(&stresses) {}

  std::string name() const override { return "constitutive"; }
  void sample(const Frame&) override {}
  void serialize(io::StateArchive&) override {}
  void write(const Frame& last, OutputSink& out) override;

 private:
  const CaseConfig* c_;
  const StripProfileObserver* profiles_;
  const CollisionStressObserver* stresses_;
};

}  // namespace grainflow::observe
