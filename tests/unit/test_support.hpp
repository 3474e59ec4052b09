// Helpers shared by the unit tests: a particle file for cases with init = "file", and an engine
// built from the text of a case.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/dem_state.hpp"

namespace grainflow::test {

// A particle file for init = "file": the `columns` line, then `rows` (one particle a line, each
// ending in '\n'), written as `name` in a folder of testing::TempDir() private to this process (the
// tests of one executable run in parallel processes under ctest) and removed with the object. The
// case loader reads the file when it loads the case, so the object need only outlive the loading.
class ParticleFile {
 public:
  ParticleFile(const std::string& name, const std::string& rows, const std::string& columns = "species,x,y,z,vx,vy,vz")
      : dir_(std::filesystem::path(testing::TempDir()) / ("grainflow_test_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / name).string();
    std::ofstream(path_) << columns << '\n' << rows;
  }
  ~ParticleFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
    std::filesystem::remove(dir_, ignored);  // only once empty: other files of this process may be there
  }
  ParticleFile(const ParticleFile&) = delete;
  ParticleFile& operator=(const ParticleFile&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::filesystem::path dir_;
  std::string path_;
};

// The engine for a loaded case, from its initial state, on `threads` threads.
inline dem::DemEngineVariant engine_for(const CaseConfig& c, int threads) {
  return dem::make_engine(c, dem::build_dem_state(c), threads);
}

// The engine for the case in `text` (`label` names it in error messages) with --set `overrides`.
inline dem::DemEngineVariant engine_from_toml(const std::string& text, const std::string& label, int threads,
                                              const std::vector<std::string>& overrides = {}) {
  return engine_for(load_case_from_string(text, label, overrides), threads);
}

}  // namespace grainflow::test
