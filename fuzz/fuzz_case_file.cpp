// libFuzzer target: any bytes as a case file. Loading and validating it must end in a CaseConfig or
// an InputError naming the file, key and reason: never a crash, a hang, an uncaught exception, a
// sanitizer report or an allocation beyond the fuzzer's memory limit.
#include <cstddef>
#include <cstdint>
#include <string>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const grainflow::CaseConfig c = grainflow::load_case_from_string(text, "fuzz.toml");
    (void)c;
  } catch (const grainflow::InputError&) {
    // refused with a message: the expected outcome for most inputs
  }
  return 0;
}
