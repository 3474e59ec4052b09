// libFuzzer target: any bytes as a particle file (particles.file). Reading it must end in particles
// or an InputError naming the line and the reason.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "grainflow/core/error.hpp"
#include "grainflow/config/particle_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const auto particles = grainflow::io::read_particle_csv(in, "fuzz.csv");
    (void)particles;
  } catch (const grainflow::InputError&) {
  }
  return 0;
}
