// The broad phase of the self-intersection test: every pair of overlapping axis-aligned boxes.
#pragma once

#include <array>
#include <utility>
#include <vector>

namespace posekit::detail {

/// A closed axis-aligned box around item `item`; its coordinates must be finite.
struct ItemBox {
  std::array<double, 3> lower;
  std::array<double, 3> upper;
  int item;
};

/// Every pair (a, b), a < b, of items whose closed boxes overlap (touching counts), each once, in no
/// particular order. A bounding-volume hierarchy over the boxes in Morton order of their centres,
/// searched against itself; large inputs in parallel.
std::vector<std::pair<int, int>> overlapping_box_pairs(const std::vector<ItemBox>& boxes);

}  // namespace posekit::detail
