#include "grainflow/observe/velocity_field.hpp"

#include <algorithm>
#include <cmath>

namespace grainflow::observe {

double FieldCell::speed() const { return std::hypot(velocity_horizontal, velocity_vertical); }

VelocityField::VelocityField(int horizontal_axis, int vertical_axis, double h_lo, double h_hi, double v_lo, double v_hi,
                             double cell, int bins)
    : h_axis_(horizontal_axis), v_axis_(vertical_axis), h_lo_(h_lo), v_lo_(v_lo), cell_(cell), bins_(bins) {
  // A cell within round-off of the far edge is not a new cell (Lan's mzcell = zcell / d exactly).
  columns_ = std::max(1, static_cast<int>(std::ceil((h_hi - h_lo) / cell - 1e-9)));
  rows_ = std::max(1, static_cast<int>(std::ceil((v_hi - v_lo) / cell - 1e-9)));
  long_term_.assign(static_cast<std::size_t>(columns_) * rows_, Sums{});
  by_bin_.assign(bins, long_term_);
}

void VelocityField::sample(const ParticleStore& p, int bin) {
  std::vector<Sums>* binned = bin >= 0 && bin < bins_ ? &by_bin_[bin] : nullptr;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    const int col = static_cast<int>(std::floor((p.position[i][h_axis_] - h_lo_) / cell_));
    const int row = static_cast<int>(std::floor((p.position[i][v_axis_] - v_lo_) / cell_));
    if (col < 0 || col >= columns_ || row < 0 || row >= rows_) continue;
    const std::size_t k = static_cast<std::size_t>(row) * columns_ + col;
    const double vh = p.velocity[i][h_axis_], vv = p.velocity[i][v_axis_];
    long_term_[k].visits += 1;
    long_term_[k].h += vh;
    long_term_[k].v += vv;
    if (binned) {
      (*binned)[k].visits += 1;
      (*binned)[k].h += vh;
      (*binned)[k].v += vv;
    }
  }
  ++samples_;
}

void VelocityField::sum_over_ranks(const RankReduce& ranks) {
  auto sum = [&](std::vector<Sums>& sums) {
    std::vector<double> flat;  // visits as doubles: exact below 2^53
    flat.reserve(3 * sums.size());
    for (const Sums& s : sums) flat.insert(flat.end(), {static_cast<double>(s.visits), s.h, s.v});
    ranks.sum(flat.data(), flat.size());
    for (std::size_t k = 0; k < sums.size(); ++k)
      sums[k] = {static_cast<long>(std::llround(flat[3 * k])), flat[3 * k + 1], flat[3 * k + 2]};
  };
  sum(long_term_);
  for (auto& bin : by_bin_) sum(bin);
}

void VelocityField::clear_sums() {
  std::fill(long_term_.begin(), long_term_.end(), Sums{});
  for (auto& bin : by_bin_) std::fill(bin.begin(), bin.end(), Sums{});
}

std::vector<FieldCell> VelocityField::cells(int bin) const {
  const auto& sums = bin < 0 ? long_term_ : by_bin_.at(bin);
  std::vector<FieldCell> out;
  out.reserve(sums.size());
  for (int row = 0; row < rows_; ++row)
    for (int col = 0; col < columns_; ++col) {
      const Sums& s = sums[static_cast<std::size_t>(row) * columns_ + col];
      FieldCell c;
      c.column = col;
      c.row = row;
      c.horizontal = h_lo_ + (col + 0.5) * cell_;
      c.vertical = v_lo_ + (row + 0.5) * cell_;
      c.visits = s.visits;
      if (s.visits > 0) {
        c.velocity_horizontal = s.h / s.visits;
        c.velocity_vertical = s.v / s.visits;
      }
      out.push_back(c);
    }
  return out;
}

double VelocityField::convection_speed() const {
  double weighted = 0.0;
  long visits = 0;
  for (const FieldCell& c : cells()) {
    weighted += c.visits * c.speed();
    visits += c.visits;
  }
  return visits > 0 ? weighted / visits : 0.0;
}

double VelocityField::cell_mean_convection_speed(double min_visit_fraction) const {
  const auto all = cells();
  long visits = 0, visited = 0;
  for (const FieldCell& c : all)
    if (c.visits > 0) visits += c.visits, ++visited;
  if (visited == 0) return 0.0;
  const double threshold =
      std::max(1.0, min_visit_fraction * static_cast<double>(visits) / static_cast<double>(visited));
  double sum = 0.0;
  long counted = 0;
  for (const FieldCell& c : all)
    if (static_cast<double>(c.visits) >= threshold) sum += c.speed(), ++counted;
  return counted > 0 ? sum / static_cast<double>(counted) : 0.0;
}

}  // namespace grainflow::observe
