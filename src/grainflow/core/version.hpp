// The grainflow version string reported by --version and written into summary.json.
#pragma once

namespace grainflow {
inline constexpr const char* kVersion = "0.1.0";
}
