#include "grainflow/run/run_support.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <numeric>

#include "grainflow/io/atomic_file.hpp"

namespace grainflow::run {

void Progress::update(double time) {
  if (!enabled_) return;
  const auto now = clock::now();
  if (now - last_ < std::chrono::milliseconds(500)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = time / elapsed;
  if (duration_ >= 1e299) {  // an event-driven run to a collision count: no end time, so no ETA
    std::fprintf(stderr, "\r  t = %.4g s   %.3g s/s   ", time, rate);
    return;
  }
  const double eta = rate > 0.0 ? (duration_ - time) / rate : 0.0;
  std::fprintf(stderr, "\r  t = %.4g / %.4g s   %.3g s/s   ETA %.0f s   ", time, duration_, rate, eta);
}

// The process's peak resident memory so far (Linux VmHWM), bytes; 0 where /proc cannot tell.
long long peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::atoll(line.c_str() + 6) * 1024LL;  // "VmHWM:  1234 kB"
  return 0;
}

int finish_summary(io::JsonObject& summary, const std::string& dir, const std::vector<std::string>& errors,
                   const std::vector<std::string>& warnings, int exit_status, bool echo_errors) {
  summary.integer("peak_memory_bytes", peak_resident_bytes());
  summary.strings("errors", errors);
  summary.strings("warnings", warnings);
  io::write_atomically(dir + "/summary.json", [&](std::ostream& out) { summary.write(out); });
  if (echo_errors)
    for (const auto& e : errors) std::cerr << "grainflow: run failed: " << e << "\n";
  return exit_status;
}

void Progress::finish() {
  if (enabled_) std::fprintf(stderr, "\n");
}

void write_final_state(const std::string& path, const ParticleStore& p, const std::vector<SpeciesConfig>& species) {
  io::write_atomically(path, [&](std::ostream& out) {
    out.precision(17);  // exact doubles: the state can be read back
    out << "# units: diameter m, x y z m, vx vy vz m/s, wx wy wz rad/s\n";
    out << "id,species,diameter,x,y,z,vx,vy,vz,wx,wy,wz\n";
    // In id order; ids need not run 0 .. N - 1 (outlets take particles out, insertions add ids).
    std::vector<std::size_t> by_id(p.size());
    std::iota(by_id.begin(), by_id.end(), std::size_t{0});
    std::sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
    for (std::size_t i : by_id) {
      const Vec3 &x = p.position[i], &v = p.velocity[i], &w = p.angular_velocity[i];
      out << p.id[i] << ',' << species[p.species[i]].name << ',' << 2.0 * p.target_radius[i] << ',' << x.x << ',' << x.y
          << ',' << x.z << ',' << v.x << ',' << v.y << ',' << v.z << ',' << w.x << ',' << w.y << ',' << w.z << '\n';
    }
  });
}

std::string join_overrides(const std::vector<std::string>& overrides) {
  std::string joined;
  for (const auto& assignment : overrides) joined += (joined.empty() ? "" : "\n") + assignment;
  return joined;
}

std::vector<std::string> split_overrides(const std::string& joined) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < joined.size()) {
    const std::size_t end = std::min(joined.find('\n', start), joined.size());
    if (end > start) out.push_back(joined.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

void write_energy_budget(const engine_api::EnergyBudget& b, double fallback_scale, io::JsonObject& summary) {
  summary.number("energy_input", b.input());
  summary.number("energy_input_gravity", b.gravity_work);
  summary.number("energy_input_walls", b.wall_work);
  summary.number("energy_input_boundaries", b.boundary_work);
  summary.number("energy_input_growth", b.growth_work);
  summary.number("energy_input_separation", b.separation_work);
  summary.number("energy_change", b.change);
  summary.number("energy_dissipated", b.dissipated);
  summary.number("energy_budget_residual", b.residual(fallback_scale));
}

}  // namespace grainflow::run
