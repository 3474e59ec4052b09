// Writes a CaseConfig back out as a case file (TOML) with every key the loader knows set to the
// value the run uses, defaults filled in and --set overrides applied, so that loading the text
// gives the same CaseConfig: OUTDIR/resolved_case.toml (docs/OUTPUTS.md).
#pragma once

#include <string>

#include "grainflow/config/case_config.hpp"

namespace grainflow {

// The case as TOML. Keys whose "not given" default has no explicit value (a sentinel such as a
// wall's restitution < 0, "the particles' value") are left out, which the loader reads the same.
// particles.file is written as an absolute path, so the text works from any folder.
std::string write_case_toml(const CaseConfig& c);

}  // namespace grainflow
