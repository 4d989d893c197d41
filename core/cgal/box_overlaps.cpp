#include "cgal/box_overlaps.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace posekit::detail {
namespace {

// A box whose id is its item, so boxes may be copied freely by the (parallel) box intersection, and
// no global counter is touched (safe when several meshes are checked at once).
class IdBox {
 public:
  using NT = double;
  using ID = std::size_t;

  IdBox() = default;
  explicit IdBox(const ItemBox& box)
      : box_(box.lower[0], box.lower[1], box.lower[2], box.upper[0], box.upper[1], box.upper[2]), item_(box.item) {}
  static int dimension() { return 3; }
  double min_coord(int axis) const { return box_.min(axis); }
  double max_coord(int axis) const { return box_.max(axis); }
  ID id() const { return static_cast<ID>(item_); }
  int item() const { return item_; }

 private:
  CGAL::Bbox_3 box_;
  int item_ = -1;
};

// CGAL's parallel box intersection works on four copies of the boxes in sixteen tasks; it only pays
// off with more than a couple of cores and more than a few thousand boxes (measured on an 84k-face mesh:
// with 2 cores the sequential search is about 10% faster).
constexpr std::size_t kParallelBoxThreshold = 4096;
constexpr int kParallelBoxMinThreads = 4;
// Boxes per leaf of CGAL's segment tree below which it scans pairs directly; 1000 was fastest on
// an 84k-face mesh; with the library's default of 10 the whole search takes 2.5 times longer.
constexpr std::ptrdiff_t kBoxCutoff = 1000;

}  // namespace

std::vector<std::pair<int, int>> overlapping_box_pairs(const std::vector<ItemBox>& item_boxes) {
  std::vector<IdBox> boxes(item_boxes.begin(), item_boxes.end());
  tbb::enumerable_thread_specific<std::vector<std::pair<int, int>>> found;
  auto collect = [&found](const IdBox& a, const IdBox& b) {
    found.local().emplace_back(std::min(a.item(), b.item()), std::max(a.item(), b.item()));
  };
  if (boxes.size() >= kParallelBoxThreshold && tbb::this_task_arena::max_concurrency() >= kParallelBoxMinThreads) {
    CGAL::box_self_intersection_d<CGAL::Parallel_tag>(boxes.begin(), boxes.end(), collect, kBoxCutoff);
  } else {
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), collect, kBoxCutoff);
  }
  std::vector<std::pair<int, int>> all;
  std::size_t total = 0;
  for (const auto& part : found) total += part.size();
  all.reserve(total);
  for (const auto& part : found) all.insert(all.end(), part.begin(), part.end());
  return all;
}

}  // namespace posekit::detail
