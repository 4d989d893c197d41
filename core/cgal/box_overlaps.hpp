// The broad phase of the self-intersection test: CGAL's box intersection over axis-aligned boxes.
#pragma once

#include <array>
#include <utility>
#include <vector>

namespace posekit::detail {

/// A closed axis-aligned box around item `item`.
struct ItemBox {
  std::array<double, 3> lower;
  std::array<double, 3> upper;
  int item;
};

/// Every pair (a, b), a < b, of items whose boxes overlap, each once, in no particular order (CGAL's
/// box_self_intersection_d; on large inputs in slabs searched in parallel).
std::vector<std::pair<int, int>> overlapping_box_pairs(const std::vector<ItemBox>& boxes);

}  // namespace posekit::detail
