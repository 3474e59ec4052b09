#include "grainflow/io/checkpoint_file.hpp"

#include <filesystem>

#include "grainflow/core/error.hpp"
#include "grainflow/io/hdf5_file.hpp"

namespace grainflow::io {
namespace {
constexpr const char* kFormat = "grainflow checkpoint 1";
std::string state_name(int rank) { return rank == 0 ? "/state" : "/state_rank_" + std::to_string(rank); }
}  // namespace

void write_checkpoint(const std::string& path, const CheckpointHeader& h, const ParticleStore& p,
                      const std::vector<std::vector<std::uint8_t>>& states, const std::vector<std::uint8_t>& portable) {
  if (states.size() != static_cast<std::size_t>(h.ranks))
    throw RunError("checkpoint: one state per MPI rank is needed");
  H5Writer file(path);
  file.attribute("/", "format", std::string(kFormat));
  file.attribute("/", "engine", h.engine);
  file.attribute("/", "dimension", static_cast<std::int64_t>(h.dimension));
  file.attribute("/", "particles", static_cast<std::int64_t>(h.particles));
  file.attribute("/", "time", h.time);
  file.attribute("/", "step", static_cast<std::int64_t>(h.step));
  file.attribute("/", "version", h.version);
  file.attribute("/", "case", h.case_path);
  file.attribute("/", "case_overrides", h.case_overrides);
  file.attribute("/", "mpi_ranks", static_cast<std::int64_t>(h.ranks));
  // For people and scripts: the particles as plain datasets, in id order of the arrays.
  file.group("/particles");
  const std::size_t n = p.size();
  auto vectors = [&](const std::string& name, const std::vector<Vec3>& v) {
    std::vector<double> flat(3 * n);
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) flat[3 * i + a] = v[i][a];
    file.write("/particles/" + name, flat, {n, 3});
  };
  vectors("position", p.position);
  vectors("velocity", p.velocity);
  vectors("angular_velocity", p.angular_velocity);
  file.write("/particles/radius", p.radius, {n});
  std::vector<std::int64_t> ids(p.id.begin(), p.id.end()), species(p.species.begin(), p.species.end());
  file.write("/particles/id", ids);
  file.write("/particles/species", species);
  for (std::size_t r = 0; r < states.size(); ++r) file.write_bytes(state_name(static_cast<int>(r)), states[r]);
  if (!portable.empty()) file.write_bytes("/portable", portable);
  file.commit();
}

namespace {
template <class Read>
void reading(const std::string& path, Read&& read) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "", "no such checkpoint file");
  try {
    H5Reader file(path);
    read(file);
  } catch (const RunError& e) {
    throw InputError(path, "", std::string("cannot read the checkpoint: ") + e.what());
  }
}

CheckpointHeader header_of(const H5Reader& file, const std::string& path) {
  CheckpointHeader h;
  if (!file.has_attribute("/", "format") || file.text("/", "format") != kFormat)
    throw InputError(path, "", "not a grainflow checkpoint (its 'format' attribute is missing or another)");
  h.engine = file.text("/", "engine");
  h.dimension = static_cast<long long>(file.number("/", "dimension"));
  h.particles = static_cast<long long>(file.number("/", "particles"));
  h.time = file.number("/", "time");
  h.step = static_cast<long long>(file.number("/", "step"));
  h.version = file.text("/", "version");
  h.case_path = file.text("/", "case");
  h.case_overrides = file.text("/", "case_overrides");
  h.ranks = file.has_attribute("/", "mpi_ranks") ? static_cast<long long>(file.number("/", "mpi_ranks")) : 1;
  return h;
}
}  // namespace

bool has_portable_state(const std::string& path) {
  bool found = false;
  reading(path, [&](const H5Reader& file) { found = file.has("/portable"); });
  return found;
}

CheckpointHeader read_checkpoint_header(const std::string& path) {
  CheckpointHeader h;
  reading(path, [&](const H5Reader& file) { h = header_of(file, path); });
  return h;
}

Checkpoint read_checkpoint(const std::string& path, int rank) {
  Checkpoint c;
  reading(path, [&](const H5Reader& file) {
    c.header = header_of(file, path);
    if (rank == kPortable) {
      if (!file.has("/portable"))
        throw InputError(path, "", "it holds no portable state (written by an older version)");
      c.state = file.read_bytes("/portable");
      c.portable = true;
    } else if (rank < c.header.ranks) {
      c.state = file.read_bytes(state_name(rank));
    }
  });
  return c;
}

}  // namespace grainflow::io
