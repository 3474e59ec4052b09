#include "grainflow/run/dem_parallel_view.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "grainflow/core/error.hpp"

namespace grainflow::run {

observe::RankReduce over_ranks(const parallel::Communicator& comm) {
  observe::RankReduce reduce;
  if (comm.size() == 1) return reduce;
  reduce.sum_in_place = [&comm](double* values, std::size_t count) { comm.sum_in_place(values, count); };
  reduce.max_over_ranks = [&comm](double local) { return comm.max(local); };
  return reduce;
}

dem::DomainDecomposition dem_grid(const dem::DemState& initial, int ranks) {
  double largest = 0.0;
  for (double r : initial.particles.target_radius) largest = std::max(largest, r);
  // Any pair a neighbour list can hold lies within 2 r_max + skin (+ an adhesive neck); a little
  // more for round-off.
  const double reach = (2.0 * largest + initial.skin + initial.cohesion_reach) * (1.0 + 1e-9);
  return dem::DomainDecomposition::balanced(initial.particles.position, initial.box, initial.gravity, ranks, reach);
}

namespace {
// What final_state.csv and a checkpoint's /particles datasets read of a particle: 97 bytes of the
// store's 184, so that rank 0's peak memory at the gather stays below a serial run's.
struct OutputRecord {
  Vec3 position, velocity, angular_velocity;
  double radius, target_radius;
  std::int32_t species;
  std::uint32_t id;
  Motion motion;
};
}  // namespace

ParticleStore gather_particles(const ParticleStore& p, const parallel::Communicator& comm) {
  std::vector<std::uint8_t> mine;
  mine.reserve(p.size() * sizeof(OutputRecord));
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.ghost[i]) continue;
    const OutputRecord r{p.position[i], p.velocity[i],      p.angular_velocity[i],
                         p.radius[i],   p.target_radius[i], p.species[i],
                         p.id[i],       p.motion[i]};
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(&r);
    mine.insert(mine.end(), bytes, bytes + sizeof r);
  }
  auto all = comm.gather(mine);
  std::vector<std::uint8_t>().swap(mine);
  ParticleStore out;
  if (!comm.root()) return out;
  std::size_t n = 0;
  for (const auto& from : all) n += from.size() / sizeof(OutputRecord);
  out.position.resize(n);
  out.velocity.resize(n);
  out.angular_velocity.resize(n);
  out.radius.resize(n);
  out.target_radius.resize(n);
  out.species.resize(n);
  out.id.resize(n);
  out.motion.resize(n);
  // Ids are 0 .. n-1 (dem::build_dem_state numbers every particle once), so each lands at its id.
  for (auto& from : all) {
    for (std::size_t at = 0; at + sizeof(OutputRecord) <= from.size(); at += sizeof(OutputRecord)) {
      OutputRecord r;
      std::memcpy(&r, from.data() + at, sizeof r);
      if (r.id >= n) throw std::logic_error("gather_particles: particle ids are not 0 .. n-1");
      out.position[r.id] = r.position;
      out.velocity[r.id] = r.velocity;
      out.angular_velocity[r.id] = r.angular_velocity;
      out.radius[r.id] = r.radius;
      out.target_radius[r.id] = r.target_radius;
      out.species[r.id] = r.species;
      out.id[r.id] = r.id;
      out.motion[r.id] = r.motion;
    }
    std::vector<std::uint8_t>().swap(from);
  }
  return out;
}

std::string fault_on_any_rank(const std::string& mine, const parallel::Communicator& comm) {
  if (!comm.any(!mine.empty())) return "";
  const auto all = comm.gather(std::vector<std::uint8_t>(mine.begin(), mine.end()));
  for (std::size_t r = 0; r < all.size(); ++r)
    if (!all[r].empty()) return "rank " + std::to_string(r) + ": " + std::string(all[r].begin(), all[r].end());
  return "a fault on another MPI rank (rank 0's summary.json has its message)";
}

dem::ContactStatistics global_statistics(const dem::ContactStatistics& local, const parallel::Communicator& comm) {
  dem::ContactStatistics g = local;
  g.max_overlap_ratio = comm.max(local.max_overlap_ratio);
  g.contacts = static_cast<long>(comm.sum(static_cast<long long>(local.contacts)));
  g.wall_contacts = static_cast<long>(comm.sum(static_cast<long long>(local.wall_contacts)));
  g.collisions = static_cast<long>(comm.sum(static_cast<long long>(local.collisions)));
  g.wall_collisions = static_cast<long>(comm.sum(static_cast<long long>(local.wall_collisions)));
  return g;
}

}  // namespace grainflow::run
