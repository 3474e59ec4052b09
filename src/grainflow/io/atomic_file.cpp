#include "grainflow/io/atomic_file.hpp"

#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "grainflow/core/error.hpp"

namespace grainflow::io {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw RunError("cannot write " + temporary);
    out.precision(10);
    write(out);
    out.flush();
    if (!out) {
      std::remove(temporary.c_str());
      throw RunError("failed while writing " + path);
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::remove(temporary.c_str());
    throw RunError("cannot rename " + temporary + " to " + path + ": " + error.message());
  }
}

}  // namespace grainflow::io
