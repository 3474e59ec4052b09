#include "grainflow/walls/triangle_tree.hpp"

#include <algorithm>
#include <numeric>

namespace grainflow::walls {
namespace {

constexpr std::uint32_t kLeafSize = 4;
// Median splits halve the count at each level, so 10^9 triangles stay far below this; the bound
// keeps the query's fixed stack (one entry per level, plus one) safe whatever the input.
constexpr int kMaxDepth = 48;

}  // namespace

TriangleTree::TriangleTree(const std::vector<Vec3>& box_lo, const std::vector<Vec3>& box_hi) {
  const auto n = static_cast<std::uint32_t>(box_lo.size());
  if (n == 0) return;
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0u);
  std::vector<Vec3> centre(n);
  for (std::uint32_t t = 0; t < n; ++t) centre[t] = 0.5 * (box_lo[t] + box_hi[t]);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  build(0, n, box_lo, box_hi, centre, 0);
}

std::uint32_t TriangleTree::build(std::uint32_t first, std::uint32_t count, const std::vector<Vec3>& lo,
                                  const std::vector<Vec3>& hi, const std::vector<Vec3>& centre, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back({});
  Node node;
  node.lo = lo[order_[first]];
  node.hi = hi[order_[first]];
  Vec3 c_lo = centre[order_[first]], c_hi = c_lo;
  for (std::uint32_t k = first; k < first + count; ++k) {
    const std::uint32_t t = order_[k];
    for (int a = 0; a < 3; ++a) {
      node.lo[a] = std::min(node.lo[a], lo[t][a]);
      node.hi[a] = std::max(node.hi[a], hi[t][a]);
      c_lo[a] = std::min(c_lo[a], centre[t][a]);
      c_hi[a] = std::max(c_hi[a], centre[t][a]);
    }
  }
  if (count <= kLeafSize || depth >= kMaxDepth) {
    node.first = first;
    node.count = count;
    nodes_[index] = node;
    return index;
  }
  // Split at the median centre along the axis the centres spread most.
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (c_hi[a] - c_lo[a] > c_hi[axis] - c_lo[axis]) axis = a;
  const std::uint32_t half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](std::uint32_t a, std::uint32_t b) {
                     return centre[a][axis] < centre[b][axis] || (centre[a][axis] == centre[b][axis] && a < b);
                   });
  build(first, half, lo, hi, centre, depth + 1);  // the left child, at index + 1
  node.first = build(first + half, count - half, lo, hi, centre, depth + 1);
  node.count = 0;
  nodes_[index] = node;
  return index;
}

}  // namespace grainflow::walls
