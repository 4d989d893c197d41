// The broad phase against the definition: every pair of closed boxes that overlap, each once.
#include "geometry/box_overlaps.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

namespace posekit::detail {
namespace {

using Pairs = std::vector<std::pair<int, int>>;

Pairs by_every_pair(const std::vector<ItemBox>& boxes) {
  Pairs pairs;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      bool overlap = true;
      for (std::size_t a = 0; a < 3; ++a) {
        overlap = overlap && boxes[i].lower[a] <= boxes[j].upper[a] && boxes[j].lower[a] <= boxes[i].upper[a];
      }
      if (overlap) pairs.emplace_back(std::min(boxes[i].item, boxes[j].item), std::max(boxes[i].item, boxes[j].item));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

Pairs sorted(Pairs pairs) {
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Boxes on a coarse lattice, so that many touch exactly at a face, an edge or a corner, some are
// points or flat, some repeat one another, and a few are long enough to cross most of the others;
// items in shuffled order.
std::vector<ItemBox> lattice_boxes(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> cell(0, 40);
  std::uniform_int_distribution<int> extent(0, 3);
  std::vector<ItemBox> boxes;
  for (int i = 0; i < count; ++i) {
    ItemBox box{};
    for (std::size_t a = 0; a < 3; ++a) {
      box.lower[a] = 0.25 * cell(random);
      box.upper[a] = box.lower[a] + 0.25 * (i % 97 == 0 ? 30 : extent(random));
    }
    box.item = i;
    boxes.push_back(box);
  }
  for (std::size_t i = 0; i + 7 < boxes.size(); i += 50) {
    boxes[i + 7].lower = boxes[i].lower;
    boxes[i + 7].upper = boxes[i].upper;
  }
  std::shuffle(boxes.begin(), boxes.end(), random);
  return boxes;
}

TEST(BoxOverlaps, FewBoxes) {
  EXPECT_TRUE(overlapping_box_pairs({}).empty());
  const ItemBox unit{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 3};
  EXPECT_TRUE(overlapping_box_pairs({unit}).empty());
  // Touching at a corner counts (closed boxes); a gap of one ulp does not.
  const ItemBox corner{{1.0, 1.0, 1.0}, {2.0, 2.0, 2.0}, 1};
  EXPECT_EQ(overlapping_box_pairs({unit, corner}), (Pairs{{1, 3}}));
  const double beyond = std::nextafter(1.0, 2.0);
  const ItemBox apart{{beyond, 0.0, 0.0}, {2.0, 1.0, 1.0}, 0};
  EXPECT_TRUE(overlapping_box_pairs({unit, apart}).empty());
}

TEST(BoxOverlaps, EveryOverlappingPairOnceOnAnyNumberOfThreads) {
  // Arenas wider than the machine: allowed, so that TBB does not warn that it caps them.
  const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 16);
  for (const int count : {2, 3, 4, 5, 40, 700, 9000}) {
    const std::vector<ItemBox> boxes = lattice_boxes(count, static_cast<unsigned>(count));
    const Pairs expected = by_every_pair(boxes);
    for (const int threads : {1, 2, 16}) {
      tbb::task_arena arena(threads);
      const Pairs found = arena.execute([&] { return overlapping_box_pairs(boxes); });
      EXPECT_EQ(found.size(), expected.size()) << count << " boxes, " << threads << " threads";
      EXPECT_EQ(sorted(found), expected) << count << " boxes, " << threads << " threads";
    }
    if (count == 9000) {
      EXPECT_GT(expected.size(), 20000u);
    }
  }
}

// Enough boxes for the parallel search, a hundred of them the same box, and boxes reaching to
// infinity along an axis; the searches run inside a caller's own parallel loop.
TEST(BoxOverlaps, RepeatedAndUnboundedBoxesInsideACallersParallelLoop) {
  std::vector<ItemBox> boxes = lattice_boxes(6000, 7u);
  for (std::size_t i = 0; i < 100; ++i) {
    boxes[i].lower = {3.0, 3.0, 3.0};
    boxes[i].upper = {3.5, 3.25, 3.0};
  }
  const double infinity = std::numeric_limits<double>::infinity();
  boxes[200].lower[0] = -infinity;
  boxes[201].upper[1] = infinity;
  const Pairs expected = by_every_pair(boxes);
  std::vector<Pairs> found(4);
  tbb::parallel_for(std::size_t{0}, found.size(),
                    [&](std::size_t k) { found[k] = sorted(overlapping_box_pairs(boxes)); });
  for (const Pairs& pairs : found) EXPECT_EQ(pairs, expected);
}

TEST(BoxOverlaps, AllBoxesAtOnePoint) {
  std::vector<ItemBox> boxes;
  for (int i = 0; i < 30; ++i) boxes.push_back({{2.0, 2.0, 2.0}, {2.0, 2.0, 2.0}, i});
  EXPECT_EQ(sorted(overlapping_box_pairs(boxes)), by_every_pair(boxes));
  EXPECT_EQ(overlapping_box_pairs(boxes).size(), 30u * 29u / 2u);
}

}  // namespace
}  // namespace posekit::detail
