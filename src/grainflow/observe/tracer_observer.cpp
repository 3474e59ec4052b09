#include "grainflow/observe/tracer_observer.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <tuple>

#include "grainflow/io/atomic_file.hpp"
#include "grainflow/observe/floor_motion.hpp"

namespace grainflow::observe {
namespace {

std::string row_text(double time, std::uint32_t id, const Vec3& x, const Vec3& v, int particles, int walls,
                     const FloorMotion& floor) {
  char line[400];
  std::snprintf(line, sizeof line, "%.10g,%u,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%d,%.10g,%.10g\n", time, id, x.x,
                x.y, x.z, v.x, v.y, v.z, particles, walls, floor.position, floor.velocity);
  return line;
}

}  // namespace

TracerObserver::TracerObserver(const RunContext& run, const ParticleStore& everyone) : run_(run) {
  const CaseConfig& c = *run.c;
  const auto& t = c.tracers;
  ids_ = t.particles;
  for (std::size_t i = 0; i < everyone.size(); ++i)
    for (const auto& name : t.species)
      if (everyone.species[i] >= 0 && static_cast<std::size_t>(everyone.species[i]) < c.species.size() &&
          c.species[everyone.species[i]].name == name)
        ids_.push_back(everyone.id[i]);
  std::sort(ids_.begin(), ids_.end());
  ids_.erase(std::unique(ids_.begin(), ids_.end()), ids_.end());
  start_ = t.start;
  const double f = c.drive.enabled ? c.drive.frequency[run.gravity_axis] : 0.0;
  interval_ = t.interval > 0.0 ? t.interval : f > 0.0 ? 1.0 / (20.0 * f) : c.output.interval;
}

void TracerObserver::sample(const Frame& now) {
  if (now.time < start_ + next_ * interval_ - 0.5 * now.time_step) return;
  const FloorMotion floor = floor_motion(now.walls, *run_.c);
  const ParticleStore& p = *now.particles;
  const auto touch = now.coordination();
  const std::size_t first = rows_.size();
  for (std::size_t i = 0; i < p.size(); ++i)  // particles are re-sorted: find them by id
    if (!p.ghost[i] && std::binary_search(ids_.begin(), ids_.end(), p.id[i]))
      rows_.push_back({next_, p.id[i],
                       row_text(now.time, p.id[i], now.box->unwrapped(p.position[i], p.image[i]), p.velocity[i],
                                touch[i].particles, touch[i].walls, floor)});
  std::sort(rows_.begin() + static_cast<std::ptrdiff_t>(first), rows_.end(),
            [](const Row& a, const Row& b) { return a.id < b.id; });
  ++next_;
}

std::vector<TracerObserver::Row> TracerObserver::gathered_rows() const {
  const parallel::Communicator& comm = *run_.comm;
  std::vector<Row> all;
  if (comm.size() == 1) return rows_;
  // Each row as sample, id, length and text; rank 0 merges them by sample, then id.
  std::vector<std::uint8_t> mine;
  auto put = [&mine](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    mine.insert(mine.end(), bytes, bytes + size);
  };
  for (const Row& r : rows_) {
    const std::uint64_t length = r.text.size();
    put(&r.sample, sizeof r.sample);
    put(&r.id, sizeof r.id);
    put(&length, sizeof length);
    put(r.text.data(), r.text.size());
  }
  for (const auto& from : comm.gather(mine)) {
    std::size_t at = 0;
    auto take = [&](void* data, std::size_t size) {
      std::memcpy(data, from.data() + at, size);
      at += size;
    };
    while (at < from.size()) {
      Row r;
      std::uint64_t length = 0;
      take(&r.sample, sizeof r.sample);
      take(&r.id, sizeof r.id);
      take(&length, sizeof length);
      r.text.assign(reinterpret_cast<const char*>(from.data() + at), length);
      at += length;
      all.push_back(std::move(r));
    }
  }
  std::sort(all.begin(), all.end(),
            [](const Row& a, const Row& b) { return std::tie(a.sample, a.id) < std::tie(b.sample, b.id); });
  return all;
}

void TracerObserver::write_rows(const OutputSink& out) const {
  const std::vector<Row> all = gathered_rows();
  if (!out.writes) return;
  io::write_atomically(out.directory + "/tracers.csv", [&](std::ostream& file) {
    file << "# tracer histories: unwrapped centre, velocity, coordination (particles touched) and walls touched, with "
            "the floor's motion\n";
    file << "# units: time s, x y z m, vx vy vz m/s, floor_position m, floor_velocity m/s\n";
    file << "time,id,x,y,z,vx,vy,vz,coordination,wall_contacts,floor_position,floor_velocity\n";
    for (const auto& r : all) file << r.text;
  });
}

}  // namespace grainflow::observe
