// Writes a file under a temporary name and renames it into place, so a crash or a failing run
// never leaves a half-written output where a complete one (or none) was.
#pragma once

#include <fstream>
#include <functional>
#include <string>

namespace grainflow::io {

// Calls `write` with a stream on `path`.tmp-<pid>, then renames onto `path`. Throws RunError on I/O failure.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace grainflow::io
