// `grainflow constitutive FOLDER... [-o FILE]`: Campbell's (1982) constitutive functions chi(nu),
// f_s(nu), f_N(nu) "collected over strips and runs" into one table: every constitutive.csv found
// under the folders (event-driven runs and sweeps), one row per strip, with the run's folder as the
// first column and whether its averages began once the flow was steady (its summary.json) second. `grainflow plot`
// draws the table beside the elastic-gas equation of state and the packing limits (Figs. 3.5, 3.21-3.24).
#pragma once

#include <string>
#include <vector>

namespace grainflow::run {

struct ConstitutiveOptions {
  std::vector<std::string> folders;
  std::string output;  // default: constitutive_table.csv in the first folder
};

// Exit status 0; throws InputError (exit 2, nothing written) when a folder is missing, holds no
// constitutive.csv, or two files' columns differ.
int collect_constitutive(const ConstitutiveOptions& options);

}  // namespace grainflow::run
