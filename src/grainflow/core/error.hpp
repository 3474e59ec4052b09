// Error types that carry what a user needs to fix a problem: the input error names file, key, reason.
// InputError means exit status 2 (nothing written); RunError means exit status 1 (outputs stay valid).
#pragma once

#include <stdexcept>
#include <string>

namespace grainflow {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string key, std::string reason)
      : std::runtime_error(file + ": " + (key.empty() ? std::string() : "key '" + key + "': ") + reason),
        file_(std::move(file)),
        key_(std::move(key)),
        reason_(std::move(reason)) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, key_, reason_;
};

class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace grainflow
