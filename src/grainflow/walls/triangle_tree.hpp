// A bounding-volume hierarchy over a mesh's triangles: the triangles near a point in O(log n) plus
// the number found, whatever the mesh's size and however its triangles' sizes vary (a large flat
// floor beside a finely curved blade), which a uniform grid does not manage.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::walls {

class TriangleTree {
 public:
  TriangleTree() = default;
  // Over triangles given by their bounding boxes.
  TriangleTree(const std::vector<Vec3>& box_lo, const std::vector<Vec3>& box_hi);

  // Calls visit(t) for each triangle t whose bounding box comes within `reach` of x.
  template <class Visit>
  void near(const Vec3& x, double reach, Visit&& visit) const {
    if (nodes_.empty()) return;
    const double reach2 = reach * reach;
    std::array<std::uint32_t, 64> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (box_distance2(node, x) > reach2) continue;
      if (node.count > 0) {
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k) visit(order_[k]);
      } else {
        stack[top++] = node.first;                                          // right child
        stack[top++] = static_cast<std::uint32_t>(&node - nodes_.data()) + 1;  // left child, next in the array
      }
    }
  }
  const Vec3& lo() const { return nodes_.front().lo; }
  const Vec3& hi() const { return nodes_.front().hi; }
  bool empty() const { return nodes_.empty(); }

 private:
  struct Node {
    Vec3 lo, hi;
    std::uint32_t first = 0;  // a leaf's first entry in order_; an inner node's right child
    std::uint32_t count = 0;  // a leaf's triangles (0: an inner node, its left child follows it)
  };
  static double box_distance2(const Node& n, const Vec3& x) {
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double below = n.lo[a] - x[a], above = x[a] - n.hi[a];
      const double d = below > 0.0 ? below : (above > 0.0 ? above : 0.0);
      d2 += d * d;
    }
    return d2;
  }
  std::uint32_t build(std::uint32_t first, std::uint32_t count, const std::vector<Vec3>& lo,
                      const std::vector<Vec3>& hi, const std::vector<Vec3>& centre, int depth);

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
};

}  // namespace grainflow::walls
