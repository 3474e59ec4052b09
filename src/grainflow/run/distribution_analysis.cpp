#include "grainflow/run/distribution_analysis.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "grainflow/analysis/pair_distribution.hpp"
#include "grainflow/analysis/velocity_distribution.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/io/json_writer.hpp"

namespace grainflow::run {

bool is_edmd_trajectory(const std::string& path) {
  const io::H5Reader h5(path);
  return h5.has_attribute("/", "engine") && h5.text("/", "engine") == "edmd";
}

analysis::StateSamples read_state_samples(const std::string& path) {
  const io::H5Reader h5(path);
  analysis::StateSamples s;
  const io::H5Array position = h5.read("/position");
  if (position.shape.size() != 3 || position.shape[2] != 3)
    throw InputError(path, "position", "expected a [samples, particles, 3] array");
  s.samples = position.shape[0];
  s.particles = position.shape[1];
  s.position = position.values;
  s.velocity = h5.read("/velocity").values;
  s.angular_velocity = h5.read("/angular_velocity").values;
  s.radius = h5.read("/radius").values;
  s.wall_lo = h5.read("/wall_lo").values;
  s.wall_hi = h5.read("/wall_hi").values;
  s.strip_lo = h5.read("/strip_lo").values;
  s.strip_hi = h5.read("/strip_hi").values;
  s.box_width = h5.read("/box_width").values;
  s.dimension = static_cast<int>(h5.number("/", "dimension"));
  s.strip_count = static_cast<int>(h5.number("/", "strip_count"));
  s.inertia_factor = h5.number("/", "inertia_factor");
  s.period_y = h5.number("/", "period_y");
  if (s.dimension == 3) {
    s.box_depth = h5.number("/", "box_depth");
    s.z_lo = h5.number("/", "z_lo");
    s.periodic_z = h5.number("/", "periodic_z") != 0.0;
  }
  const std::size_t values = s.samples * s.particles * 3;
  for (const auto* field : {&s.velocity, &s.angular_velocity})
    if (field->size() != values) throw InputError(path, "velocity", "the per-particle arrays differ in shape");
  for (const auto* field : {&s.wall_lo, &s.wall_hi, &s.strip_lo, &s.strip_hi, &s.box_width})
    if (field->size() != s.samples) throw InputError(path, "wall_lo", "the per-sample arrays differ in length");
  if (s.radius.size() != s.particles) throw InputError(path, "radius", "needs one radius per followed particle");
  return s;
}

void analyze_distributions(const std::string& output_directory, const AnalyzeOptions& options) {
  namespace fs = std::filesystem;
  const fs::path dir(output_directory), file = dir / "trajectory.h5";
  const analysis::StateSamples s = read_state_samples(file.string());
  if (s.samples < 1 || s.particles == 0)
    throw InputError(file.string(), "samples", "holds no samples: the run ended before trajectory.start");
  if (options.first_strip >= s.strip_count || (options.last_strip >= 0 && options.last_strip < options.first_strip) ||
      options.last_strip >= s.strip_count)
    throw InputError(file.string(), "--strips",
                     "must name strips in [0, " + std::to_string(s.strip_count - 1) + "], first <= last (the run has " +
                         std::to_string(s.strip_count) + " strips)");
  analysis::VelocityDistributionOptions vo;
  vo.first_strip = options.first_strip;
  vo.last_strip = options.last_strip;
  const auto v = analysis::velocity_distributions(s, vo);
  const bool all_followed =
      static_cast<std::size_t>(io::H5Reader(file.string()).number("/", "particles_total")) == s.particles;

  io::write_atomically((dir / "analysis" / "velocity_distributions.csv").string(), [&](std::ostream& out) {
    out << "# velocity distributions (Campbell 1982 section 3.4.1) over " << s.samples << " samples, strips "
        << v.first_strip << ".." << v.last_strip << " of " << s.strip_count << " (" << v.counted
        << " particle samples): X = |q - <q>_strip| / sqrt(<q'^2>_strip), combinations as sqrt(energy / mean energy)\n";
    out << "# variables:";
    for (const auto& x : v.variables) out << ' ' << x.name << " = (" << x.components_text << ")";
    out << "\n# units: x dimensionless (bin centre, bins of " << v.bin_width
        << "); p densities 1/x with integral over [0, inf) = 1: measured, least-squares generalized Maxwellian (fit),"
           " Maxwellian a = k/2 (maxwell)\n";
    out << 'x';
    for (std::size_t i = 1; i <= v.variables.size(); ++i) out << ",p" << i << ",p" << i << "_fit,p" << i << "_maxwell";
    out << '\n' << std::setprecision(10);
    for (std::size_t b = 0; b < v.x.size(); ++b) {
      out << v.x[b];
      for (const auto& x : v.variables) {
        const int k = static_cast<int>(x.components.size());
        out << ',' << x.density[b] << ',' << analysis::generalized_maxwellian(k, x.fit.a, v.x[b]) << ','
            << analysis::generalized_maxwellian(k, x.maxwell_a(), v.x[b]);
      }
      out << '\n';
    }
  });

  io::JsonObject json;
  json.string("trajectory", file.string());
  json.integer("dimension", s.dimension);
  json.integer("samples", static_cast<long long>(s.samples));
  json.integer("particles", static_cast<long long>(s.particles));
  json.integer("strips", s.strip_count);
  json.integer("first_strip", v.first_strip);
  json.integer("last_strip", v.last_strip);
  json.integer("particle_samples", v.counted);
  json.number("diameter", v.diameter);
  json.number("inertia_factor", s.inertia_factor);
  for (std::size_t i = 0; i < v.variables.size(); ++i) {
    const auto& x = v.variables[i];
    std::string a = "a";
    a += std::to_string(i + 1);
    json.string(a + "_components", x.components_text);
    json.number(a, x.fit.a);
    json.number(a + "_error", x.fit.error);
    json.number(a + "_maxwell", x.maxwell_a());
    json.number(a + "_ratio", x.fit.a / x.maxwell_a());
    json.number(a + "_ratio_error", x.fit.error / x.maxwell_a());
  }
  json.number("shear_rate", v.shear_rate);
  json.number("u_fluctuation_square", v.u2);
  json.number("v_fluctuation_square", v.v2);
  json.number("s", v.s_u);
  json.number("s_uv", v.s_uv);

  std::cout << std::setprecision(4) << "velocity distributions (" << v.counted << " particle samples, strips "
            << v.first_strip << ".." << v.last_strip << "): a (a / a_m)\n";
  for (std::size_t i = 0; i < v.variables.size(); ++i) {
    const auto& x = v.variables[i];
    std::cout << "  " << x.name << " (" << x.components_text << "): " << x.fit.a << " +- " << x.fit.error << "  ("
              << x.fit.a / x.maxwell_a() << ")\n";
  }
  std::cout << "  S = 2R du/dy / sqrt<u'^2> = " << v.s_u << ", 2R du/dy / sqrt(<u'^2> + <v'^2>) = " << v.s_uv << "\n";

  if (all_followed) {
    const auto p = analysis::pair_distributions(s, {});
    const double r = 0.5 * p.diameter;
    const double solids = p.number_density * (s.dimension == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r);
    io::write_atomically((dir / "analysis" / "pair_distributions.csv").string(), [&](std::ostream& out) {
      out << "# pair distributions (Campbell 1982 section 3.4.3): number density at distance r from test particles"
             " (centres within a diameter of the midplane between the walls; "
          << p.test_particles_per_sample << " per sample over " << s.samples
          << " samples); normal: by |dy|; parallel: particles within a diameter in y, by the forward periodic distance"
             " along x; parallel_two_sided: by the nearest-image |dx|; empty slices (no region) are nan\n";
      out << "# units: r m (slice centre, slices of " << p.slice << " m), densities, their standard errors (block"
          << " averages over the samples) and number_density (the cell's: N / (gap x width"
          << (s.dimension == 3 ? " x depth" : "") << ")) 1/m^" << s.dimension << "\n";
      out << "r,normal,normal_error,parallel,parallel_error,parallel_two_sided,parallel_two_sided_error,number_"
             "density\n"
          << std::setprecision(10);
      for (std::size_t k = 0; k < p.r.size(); ++k)
        out << p.r[k] << ',' << p.normal[k] << ',' << p.normal_error[k] << ',' << p.parallel[k] << ','
            << p.parallel_error[k] << ',' << p.parallel_two_sided[k] << ',' << p.parallel_two_sided_error[k] << ','
            << p.number_density << '\n';
    });
    json.number("number_density", p.number_density);
    json.number("solids_fraction", solids);
    json.number("band_number_density", p.band_number_density);
    json.number("test_particles_per_sample", p.test_particles_per_sample);
    json.number("pair_range", p.slice * static_cast<double>(p.r.size()));
    json.integer("pair_slices", static_cast<long long>(p.r.size()));
    std::cout << "pair distributions: " << p.test_particles_per_sample
              << " test particles per sample, n = " << p.number_density << " (nu = " << solids
              << "), midplane band n = " << p.band_number_density << "\n";
  } else {
    std::cout << "pair distributions: skipped (trajectory.particles follows " << s.particles
              << " particles, not all of them)\n";
  }
  io::write_atomically((dir / "analysis" / "distributions.json").string(), [&](std::ostream& out) { json.write(out); });
  std::cout << "(written to " << (dir / "analysis").string() << "/)\n";
}

}  // namespace grainflow::run
