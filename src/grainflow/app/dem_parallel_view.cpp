#include "grainflow/app/dem_parallel_view.hpp"

#include <algorithm>
#include <cstring>

#include "grainflow/core/error.hpp"

namespace grainflow::app {

observe::RankReduce over_ranks(const parallel::Communicator& comm) {
  observe::RankReduce reduce;
  if (comm.size() == 1) return reduce;
  reduce.sum_in_place = [&comm](double* values, std::size_t count) { comm.sum_in_place(values, count); };
  reduce.max_over_ranks = [&comm](double local) { return comm.max(local); };
  return reduce;
}

dem::SlabDecomposition dem_slabs(const dem::DemState& initial, int ranks) {
  double largest = 0.0;
  for (double r : initial.particles.target_radius) largest = std::max(largest, r);
  // Any pair a neighbour list can hold lies within 2 r_max + skin; a little more for round-off.
  const double reach = (2.0 * largest + initial.skin) * (1.0 + 1e-9);
  return dem::SlabDecomposition::balanced(initial.particles.position, initial.box, initial.gravity, ranks, reach);
}

void gather_view(const dem::DemState& local, const parallel::Communicator& comm, dem::DemState& view) {
  const ParticleStore& p = local.particles;
  std::vector<std::uint8_t> mine;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.ghost[i]) continue;
    const ParticleStore::Record r = p.record(i);
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(&r);
    mine.insert(mine.end(), bytes, bytes + sizeof r);
  }
  const auto all = comm.gather(mine);
  view.box = local.box;
  view.gravity = local.gravity;
  view.time = local.time;
  view.time_step = local.time_step;
  view.step = local.step;
  view.skin = local.skin;
  view.walls = local.walls;
  view.bump_velocity = local.bump_velocity;
  view.bump_displacement = local.bump_displacement;
  view.expansion_rate = local.expansion_rate;
  view.species = local.species;
  std::vector<ParticleStore::Record> records;
  for (const auto& from : all)
    for (std::size_t at = 0; at + sizeof(ParticleStore::Record) <= from.size(); at += sizeof(ParticleStore::Record)) {
      ParticleStore::Record r;
      std::memcpy(&r, from.data() + at, sizeof r);
      records.push_back(r);
    }
  std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  view.particles = ParticleStore{};
  for (const auto& r : records) view.particles.push_back(r);
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

}  // namespace grainflow::app
