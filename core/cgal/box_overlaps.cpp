#include "cgal/box_overlaps.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace posekit::detail {
namespace {

// A box whose id is its item, so boxes may be copied freely by the box intersection, and no global
// counter is touched (safe when several meshes are checked at once).
class IdBox {
 public:
  using NT = double;
  using ID = std::size_t;

  IdBox() = default;
  explicit IdBox(const ItemBox& box, int first_slab = 0)
      : box_(box.lower[0], box.lower[1], box.lower[2], box.upper[0], box.upper[1], box.upper[2]),
        item_(box.item),
        first_slab_(first_slab) {}
  static int dimension() { return 3; }
  double min_coord(int axis) const { return box_.min(axis); }
  double max_coord(int axis) const { return box_.max(axis); }
  ID id() const { return static_cast<ID>(item_); }
  int item() const { return item_; }
  /// The slab that holds the box's lower end (slab_search below).
  int first_slab() const { return first_slab_; }

 private:
  CGAL::Bbox_3 box_;
  int item_ = -1;
  int first_slab_ = 0;
};

using Pairs = std::vector<std::pair<int, int>>;

// Below this many boxes one search on the calling thread is as fast as any split.
constexpr std::size_t kSlabBoxThreshold = 4096;
// Slabs per thread: more than one, so that a slab denser than the others leaves no thread idle for long.
constexpr int kSlabsPerThread = 2;
// Boxes per leaf of CGAL's segment tree below which it scans pairs directly; 1000 was fastest on
// an 84k-face mesh; with the library's default of 10 the whole search takes 2.5 times longer.
constexpr std::ptrdiff_t kBoxCutoff = 1000;

// CGAL's sequential search; `keep(a, b)` decides which of the overlapping pairs are reported.
template <class Keep>
void search(std::vector<IdBox>& boxes, Keep&& keep, Pairs& found) {
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(
      boxes.begin(), boxes.end(),
      [&](const IdBox& a, const IdBox& b) {
        if (keep(a, b)) found.emplace_back(std::min(a.item(), b.item()), std::max(a.item(), b.item()));
      },
      kBoxCutoff);
}

// The axis along which the boxes' lower corners spread the most.
int widest_axis(const std::vector<ItemBox>& boxes) {
  std::array<double, 3> low = boxes.front().lower;
  std::array<double, 3> high = boxes.front().lower;
  for (const ItemBox& box : boxes) {
    for (size_t a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], box.lower[a]);
      high[a] = std::max(high[a], box.lower[a]);
    }
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (high[static_cast<size_t>(a)] - low[static_cast<size_t>(a)] >
        high[static_cast<size_t>(axis)] - low[static_cast<size_t>(axis)]) {
      axis = a;
    }
  }
  return axis;
}

// The boxes cut into slabs across their widest axis, each slab searched on its own and the slabs in
// parallel. A box joins every slab its extent meets; a pair is kept only by the slab that holds the
// lower end of the two boxes' common interval on that axis, a point both boxes contain, so each pair
// is found exactly once. That end is the larger of the two lower ends, so its slab is the later of
// the two boxes' first slabs. (CGAL's own parallel search copies the boxes four times into sixteen tasks
// and was slower than its sequential search on 2 cores.)
Pairs slab_search(const std::vector<ItemBox>& item_boxes, int slab_count) {
  const auto axis = static_cast<size_t>(widest_axis(item_boxes));
  // Boundaries at quantiles of the lower ends, so that the slabs hold about as many boxes each.
  std::vector<double> lower_ends(item_boxes.size());
  for (size_t i = 0; i < item_boxes.size(); ++i) lower_ends[i] = item_boxes[i].lower[axis];
  std::vector<double> boundaries;  // slab k holds [boundaries[k - 1], boundaries[k])
  for (int k = 1; k < slab_count; ++k) {
    const auto at = lower_ends.begin() + static_cast<std::ptrdiff_t>(lower_ends.size() * static_cast<size_t>(k) /
                                                                   static_cast<size_t>(slab_count));
    std::nth_element(lower_ends.begin(), at, lower_ends.end());
    boundaries.push_back(*at);
  }
  std::sort(boundaries.begin(), boundaries.end());
  const auto slab_of = [&boundaries](double x) {
    return static_cast<int>(std::upper_bound(boundaries.begin(), boundaries.end(), x) - boundaries.begin());
  };

  std::vector<std::vector<IdBox>> slabs(static_cast<size_t>(slab_count));
  for (const ItemBox& box : item_boxes) {
    const int first = slab_of(box.lower[axis]);
    const int last = slab_of(box.upper[axis]);
    for (int k = first; k <= last; ++k) slabs[static_cast<size_t>(k)].emplace_back(box, first);
  }
  std::vector<Pairs> found(static_cast<size_t>(slab_count));
  tbb::parallel_for(0, slab_count, [&](int k) {
    const auto in_slab = [k](const IdBox& a, const IdBox& b) { return std::max(a.first_slab(), b.first_slab()) == k; };
    search(slabs[static_cast<size_t>(k)], in_slab, found[static_cast<size_t>(k)]);
  });
  Pairs all;
  size_t total = 0;
  for (const Pairs& part : found) total += part.size();
  all.reserve(total);
  for (const Pairs& part : found) all.insert(all.end(), part.begin(), part.end());
  return all;
}

}  // namespace

std::vector<std::pair<int, int>> overlapping_box_pairs(const std::vector<ItemBox>& item_boxes) {
  const int threads = tbb::this_task_arena::max_concurrency();
  if (item_boxes.size() >= kSlabBoxThreshold && threads > 1) {
    return slab_search(item_boxes, kSlabsPerThread * threads);
  }
  std::vector<IdBox> boxes(item_boxes.begin(), item_boxes.end());
  Pairs found;
  search(boxes, [](const IdBox&, const IdBox&) { return true; }, found);
  return found;
}

}  // namespace posekit::detail
