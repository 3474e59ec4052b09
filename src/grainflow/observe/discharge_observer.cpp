#include "grainflow/observe/discharge_observer.hpp"

#include <cmath>
#include <iomanip>

#include "grainflow/core/ball_measure.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/json_writer.hpp"

namespace grainflow::observe {

DischargeRate steady_discharge_rate(const std::vector<double>& time, const std::vector<double>& mass) {
  DischargeRate d;
  constexpr int kBlocks = 8;
  if (time.size() < 2 * kBlocks || mass.back() <= 0.0) return d;
  const auto first_reaching = [&](double fraction) {
    std::size_t k = 0;
    while (k + 1 < mass.size() && mass[k] < fraction * mass.back()) ++k;
    return k;
  };
  const bool steady_from_start = mass.front() > 0.2 * mass.back();  // cannot tell: use all
  const std::size_t a = steady_from_start ? 0 : first_reaching(0.2), b = first_reaching(0.8);
  if (b < a + kBlocks) return d;
  // Least squares slope over [a, b].
  double st = 0.0, sm = 0.0, stt = 0.0, stm = 0.0;
  const double n = static_cast<double>(b - a + 1);
  for (std::size_t k = a; k <= b; ++k) {
    st += time[k];
    sm += mass[k];
    stt += time[k] * time[k];
    stm += time[k] * mass[k];
  }
  d.rate = (stm - st * sm / n) / (stt - st * st / n);
  double sum = 0.0, sum2 = 0.0;
  for (int block = 0; block < kBlocks; ++block) {
    const std::size_t from = a + (b - a) * block / kBlocks, to = a + (b - a) * (block + 1) / kBlocks;
    const double r = (mass[to] - mass[from]) / (time[to] - time[from]);
    sum += r;
    sum2 += r * r;
  }
  const double mean = sum / kBlocks;
  d.error = std::sqrt(std::max(0.0, sum2 / kBlocks - mean * mean) / (kBlocks - 1));
  d.start = time[a];
  d.end = time[b];
  d.measured = true;
  return d;
}

DischargeObserver::DischargeObserver(const RunContext& run)
    : ranks_(run.ranks), schedule_(run.c->output.interval, run.time_step) {
  for (const OutletConfig& o : run.c->outlets) {
    names_.push_back(o.name);
    if (o.has_bed && !has_bed_) has_bed_ = true, bed_lo_ = o.bed_lo, bed_hi_ = o.bed_hi;
  }
  dimension_ = run.c->engine.dimension;
}

void DischargeObserver::take(const Frame& now) {
  std::vector<double> row(2 * names_.size(), 0.0);
  if (now.outlet_counts) {
    const std::vector<OutletTally> counts = now.outlet_counts();
    for (std::size_t o = 0; o < counts.size() && o < names_.size(); ++o) {
      row[2 * o] = static_cast<double>(counts[o].removed);
      row[2 * o + 1] = counts[o].mass;
    }
  }
  if (has_bed_ && now.particles) {  // the particles' volume with centres in the box, over its volume
    const ParticleStore& p = *now.particles;
    double solid = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!p.counted(i)) continue;
      const Vec3& x = p.position[i];
      bool inside = true;
      for (int a = 0; a < dimension_; ++a) inside = inside && x[a] >= bed_lo_[a] && x[a] <= bed_hi_[a];
      if (inside) solid += ball_measure(dimension_, p.radius[i]);
    }
    row.push_back(solid);
  }
  ranks_.sum(row.data(), row.size());
  if (has_bed_) {
    double volume = 1.0;
    for (int a = 0; a < dimension_; ++a) volume *= bed_hi_[a] - bed_lo_[a];
    bed_fraction_.push_back(row.back() / volume);
    row.pop_back();
  }
  values_.push_back(now.time);
  values_.insert(values_.end(), row.begin(), row.end());
}

void DischargeObserver::write_file(const OutputSink& out) const {
  if (!out.writes || names_.empty()) return;
  const std::size_t width = 1 + 2 * names_.size();
  io::write_atomically(out.directory + "/discharge.csv", [&](std::ostream& file) {
    file << "# units: time s, removed_mass kg (kg/m for discs); removed and removed_mass count every particle "
            "each [[outlet]] has removed since the start\n";
    file << "time,outlet,removed,removed_mass\n";
    file << std::setprecision(12);
    for (std::size_t s = 0; s + width <= values_.size(); s += width)
      for (std::size_t o = 0; o < names_.size(); ++o)
        file << values_[s] << ',' << names_[o] << ',' << static_cast<long>(values_[s + 1 + 2 * o]) << ','
             << values_[s + 2 + 2 * o] << '\n';
  });
}

void DischargeObserver::write(const Frame& last, OutputSink& out) {
  (void)last;
  write_file(out);
  if (!out.summary || names_.empty()) return;
  const std::size_t width = 1 + 2 * names_.size();
  std::vector<double> time, mass;
  double removed = 0.0;
  for (std::size_t s = 0; s + width <= values_.size(); s += width) {
    time.push_back(values_[s]);
    double m = 0.0;
    removed = 0.0;
    for (std::size_t o = 0; o < names_.size(); ++o) {
      removed += values_[s + 1 + 2 * o];
      m += values_[s + 2 + 2 * o];
    }
    mass.push_back(m);
  }
  out.summary->integer("discharged", static_cast<long long>(removed));
  out.summary->number("discharged_mass", mass.empty() ? 0.0 : mass.back());
  const DischargeRate d = steady_discharge_rate(time, mass);
  if (!d.measured) {
    if (out.warnings) out.warnings->push_back("discharge_rate: too few samples or nothing discharged to measure a rate");
    return;
  }
  if (has_bed_) {  // over the rate's window: blocks of it give the error, as for the rate
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < time.size() && k < bed_fraction_.size(); ++k)
      if (time[k] >= d.start && time[k] <= d.end) sum += bed_fraction_[k], sum2 += bed_fraction_[k] * bed_fraction_[k], ++n;
    if (n > 1) {
      const double mean = sum / n;
      out.summary->number("bulk_solids_fraction", mean);
      out.summary->number("bulk_solids_fraction_std", std::sqrt(std::max(0.0, sum2 / n - mean * mean)));
    }
  }
  out.summary->number("discharge_rate", d.rate);
  out.summary->number("discharge_rate_error", d.error);
  out.summary->number("discharge_window_start", d.start);
  out.summary->number("discharge_window_end", d.end);
}

}  // namespace grainflow::observe
