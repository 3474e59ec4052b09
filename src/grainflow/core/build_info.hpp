// Facts about the build, for run_log.json. The commit is read when CMake configures (not at every
// build, so a new commit does not recompile anything): after committing, re-run `cmake --preset
// release` for run_log.json to name the new commit. "unknown" outside a git checkout.
#pragma once

namespace grainflow {
extern const char* const kGitCommit;  // `git rev-parse --short HEAD` at configure time
}
