// Helpers of the tests of an observer's own case table: a bundled case with one line edited,
// loaded through the case loader (the registered observers' schemas), and the InputError it must
// raise naming the case file, the key and the reason.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "grainflow/config/case_parser.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/run/case_loader.hpp"

namespace grainflow::test {

// cases/NAME under the source tree.
inline std::string bundled_case(const std::string& name) {
  return std::string(GRAINFLOW_SOURCE_DIR) + "/cases/" + name;
}

// The case at `path` with the one occurrence of `from` replaced by `to`, loaded.
inline CaseConfig load_edited_case(const std::string& path, const std::string& from, const std::string& to) {
  std::string text = read_case_file(path);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in " << path;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return load_case_from_string(text, path);
}

// The edited case must be refused with an InputError naming the case file, `key` and `reason_part`.
inline void expect_refused(const std::string& path, const std::string& from, const std::string& to,
                           const std::string& key, const std::string& reason_part) {
  try {
    load_edited_case(path, from, to);
    ADD_FAILURE() << "expected InputError for key '" << key << "', but the case loaded";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path) << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.reason().find(reason_part), std::string::npos) << e.what();
  }
}

}  // namespace grainflow::test
