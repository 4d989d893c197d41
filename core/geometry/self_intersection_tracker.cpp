#include "cgal/face_pair_test.hpp"
#include "geometry/face_bounds.hpp"
#include "geometry/vertex_checks.hpp"

#include <posekit/error.hpp>
#include <posekit/self_intersection_tracker.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

namespace posekit {
namespace {

struct Box {
  std::array<double, 3> min{};
  std::array<double, 3> max{};

  bool overlaps(const Box& other) const {
    for (int axis = 0; axis < 3; ++axis) {
      if (min[axis] > other.max[axis] || other.min[axis] > max[axis]) return false;
    }
    return true;
  }
  double extent() const { return std::max({max[0] - min[0], max[1] - min[1], max[2] - min[2]}); }
};

Box face_box(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
             int f) {
  const detail::FaceBounds bounds = detail::face_bounds(vertices, faces, f);
  return {bounds.lower, bounds.upper};
}

// The finest cell is the 95th percentile of the faces' box widths: most faces lie in it, and a query
// for a face of common size looks at no more than 27 cells; the wider few go to coarser levels.
constexpr double kCellQuantile = 0.95;
// Cell indices are packed into 21 bits per axis, counted from the first pose's lower corner; moves
// beyond that range clamp to the border cells, which stays correct (queries clamp alike).
constexpr std::int64_t kCellsPerAxis = std::int64_t{1} << 21;
// Below this many moved faces the re-test runs on the calling thread.
constexpr std::size_t kParallelFaces = 256;
// Beyond this fraction of the faces moved, testing the pose whole is cheaper.
constexpr double kWholeTestFraction = 0.25;

void sort_unique(FacePairs& pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}


// An item stored with its box, so that a query reads the boxes of a cell one after another rather
// than looking each up in a table of the whole mesh's boxes (a cache miss per item on a large mesh).
struct BoxedItem {
  Box box;
  int item = 0;
};

// Items (faces) bucketed by the grid cell of their box's lower corner: an item whose box is at most a
// cell wide overlaps a query box only if its lower corner lies within one cell below the query's.
// Items wider than a cell go to a coarser level of cells kCoarserFactor times as wide, and so on:
// kept in one list instead, the few percent of wide faces of a large mesh were scanned by every query
// and cost more than the rest of it. The cells are an open-addressing table: a query probes up to 27
// cells, most of them empty, and a miss costs one probe of a flat array instead of a node hash.
class Buckets {
 public:
  Buckets(double cell, const std::array<double, 3>& origin, int level = 0)
      : cell_(cell), origin_(origin), level_(level) {}
  Buckets(const Buckets& other)
      : cell_(other.cell_),
        origin_(other.origin_),
        level_(other.level_),
        slots_(other.slots_),
        occupied_(other.occupied_),
        shift_(other.shift_),
        oversized_(other.oversized_),
        coarser_(other.coarser_ ? std::make_unique<Buckets>(*other.coarser_) : nullptr) {}
  Buckets& operator=(const Buckets& other) {
    if (this != &other) *this = Buckets(other);
    return *this;
  }
  Buckets(Buckets&&) noexcept = default;
  Buckets& operator=(Buckets&&) noexcept = default;
  ~Buckets() = default;

  void insert(int item, const Box& box) {
    if (box.extent() <= cell_) {
      cell_items(key_of(box)).push_back({box, item});
    } else if (level_ + 1 < kLevels) {
      if (!coarser_) coarser_ = std::make_unique<Buckets>(cell_ * kCoarserFactor, origin_, level_ + 1);
      coarser_->insert(item, box);
    } else {
      oversized_.push_back({box, item});
    }
  }

  void erase(int item, const Box& box) {
    if (box.extent() > cell_ && level_ + 1 < kLevels) {
      if (coarser_) coarser_->erase(item, box);
      return;
    }
    std::vector<BoxedItem>* bucket = box.extent() > cell_ ? &oversized_ : find(key_of(box));
    if (bucket == nullptr) return;
    const auto found =
        std::find_if(bucket->begin(), bucket->end(), [item](const BoxedItem& stored) { return stored.item == item; });
    if (found != bucket->end()) {
      *found = bucket->back();
      bucket->pop_back();
    }
  }

  // Calls visit(item) for every stored item whose box overlaps `box`. A box wider than the occupied
  // cells are many (a face stretched across the pose) visits those cells instead of its range.
  template <class Visit>
  void query(const Box& box, Visit&& visit) const {
    std::array<std::int64_t, 3> low{};
    std::array<std::int64_t, 3> high{};
    double range_cells = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
      low[axis] = index(axis, box.min[axis] - cell_);
      high[axis] = index(axis, box.max[axis]);
      range_cells *= static_cast<double>(high[axis] - low[axis] + 1);
    }
    const auto visit_bucket = [&](const std::vector<BoxedItem>& bucket) {
      for (const BoxedItem& stored : bucket) {
        if (stored.box.overlaps(box)) visit(stored.item);
      }
    };
    if (range_cells > static_cast<double>(occupied_)) {
      for (const Slot& slot : slots_) {
        if (slot.key != kNoKey) visit_bucket(slot.items);
      }
    } else {
      for (std::int64_t x = low[0]; x <= high[0]; ++x) {
        for (std::int64_t y = low[1]; y <= high[1]; ++y) {
          for (std::int64_t z = low[2]; z <= high[2]; ++z) {
            if (const std::vector<BoxedItem>* bucket = find(key(x, y, z))) visit_bucket(*bucket);
          }
        }
      }
    }
    visit_bucket(oversized_);
    if (coarser_) coarser_->query(box, visit);
  }

 private:
  // Each level's cells are this many times as wide as the finer level's; past the last level, wide
  // items are kept in a list (a face across the whole pose).
  static constexpr double kCoarserFactor = 4.0;
  static constexpr int kLevels = 8;
  // No packed key has all 64 bits set (three 21-bit indices), so it marks a free slot. A cell once
  // added keeps its slot (erase only empties its items), so probing needs no tombstones.
  static constexpr std::uint64_t kNoKey = ~std::uint64_t{0};
  static_assert(3 * 21 < 64, "packed cell keys must leave the free-slot mark unused");
  static constexpr std::size_t kFirstSlots = 64;

  struct Slot {
    std::uint64_t key = kNoKey;
    std::vector<BoxedItem> items;
  };

  // Index of `coordinate` along `axis`, clamped to the grid.
  std::int64_t index(int axis, double coordinate) const {
    const double steps = std::floor((coordinate - origin_[axis]) / cell_);
    return static_cast<std::int64_t>(std::clamp(steps, 0.0, static_cast<double>(kCellsPerAxis - 1)));
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) << 42) | (static_cast<std::uint64_t>(y) << 21) | static_cast<std::uint64_t>(z);
  }
  std::uint64_t key_of(const Box& box) const {
    return key(index(0, box.min[0]), index(1, box.min[1]), index(2, box.min[2]));
  }

  // Fibonacci hashing: neighbouring cells' keys differ in their low bits of each index, which the
  // multiplication spreads over the top bits the slot is taken from.
  std::size_t home(std::uint64_t cell_key) const {
    return static_cast<std::size_t>((cell_key * 0x9E3779B97F4A7C15ULL) >> shift_);
  }

  const std::vector<BoxedItem>* find(std::uint64_t cell_key) const {
    if (slots_.empty()) return nullptr;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = home(cell_key);; i = (i + 1) & mask) {
      const Slot& slot = slots_[i];
      if (slot.key == cell_key) return &slot.items;
      if (slot.key == kNoKey) return nullptr;
    }
  }
  std::vector<BoxedItem>* find(std::uint64_t cell_key) {
    return const_cast<std::vector<BoxedItem>*>(std::as_const(*this).find(cell_key));
  }

  // The items of a cell, the cell added if new. The table stays at most half full.
  std::vector<BoxedItem>& cell_items(std::uint64_t cell_key) {
    if (2 * (occupied_ + 1) > slots_.size()) grow();
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = home(cell_key);; i = (i + 1) & mask) {
      Slot& slot = slots_[i];
      if (slot.key == cell_key) return slot.items;
      if (slot.key == kNoKey) {
        slot.key = cell_key;
        ++occupied_;
        return slot.items;
      }
    }
  }

  void grow() {
    std::vector<Slot> old = std::move(slots_);
    const std::size_t size = old.empty() ? kFirstSlots : 2 * old.size();
    slots_ = std::vector<Slot>(size);
    shift_ = 64;
    for (std::size_t s = size; s > 1; s >>= 1) --shift_;
    const std::size_t mask = size - 1;
    for (Slot& moved : old) {
      if (moved.key == kNoKey) continue;
      std::size_t i = home(moved.key);
      while (slots_[i].key != kNoKey) i = (i + 1) & mask;
      slots_[i] = std::move(moved);
    }
  }

  double cell_;
  std::array<double, 3> origin_;
  int level_;
  std::vector<Slot> slots_;
  std::size_t occupied_ = 0;
  int shift_ = 64;
  std::vector<BoxedItem> oversized_;
  std::unique_ptr<Buckets> coarser_;
};

// A cell as wide as most faces' boxes, from the lower corner of all the boxes (not of the whole pose:
// the moved faces' own buckets need no pass over every vertex).
Buckets buckets_for(const std::vector<Box>& boxes) {
  std::vector<double> extents(boxes.size());
  for (size_t f = 0; f < boxes.size(); ++f) extents[f] = boxes[f].extent();
  double cell = 0.0;
  if (!extents.empty()) {
    const auto quantile =
        extents.begin() + static_cast<std::ptrdiff_t>(kCellQuantile * static_cast<double>(extents.size() - 1));
    std::nth_element(extents.begin(), quantile, extents.end());
    cell = *quantile;
  }
  if (!(cell > 0.0)) cell = 1.0;  // every face a point: any cell works
  std::array<double, 3> origin{};
  if (!boxes.empty()) origin = boxes.front().min;
  for (const Box& box : boxes) {
    for (int axis = 0; axis < 3; ++axis) origin[axis] = std::min(origin[axis], box.min[axis]);
  }
  return {cell, origin};
}

}  // namespace

// The pose last tested, its faces' boxes in buckets, and which faces are degenerate. The faces are
// the tracker's own copy, shared by its copies, so that the caller's matrix need not outlive it.
class SelfIntersectionTracker::Grid {
 public:
  Grid(const Eigen::Ref<const Eigen::MatrixX3d>& pose, std::shared_ptr<const Eigen::MatrixX3i> mesh_faces_copy)
      : Grid(pose, mesh_faces_copy, *mesh_faces_copy) {}

  Grid(const Eigen::Ref<const Eigen::MatrixX3d>& pose, std::shared_ptr<const Eigen::MatrixX3i> mesh_faces_copy,
       const Eigen::MatrixX3i& mesh_faces)
      : vertices(pose),
        faces(std::move(mesh_faces_copy)),
        faces_of_vertex(vertex_faces(mesh_faces, static_cast<int>(pose.rows()))),
        boxes(static_cast<size_t>(mesh_faces.rows())),
        degenerate(static_cast<size_t>(mesh_faces.rows()), 0),
        buckets(1.0, {}) {
    const detail::FacePairTest test(vertices, mesh_faces);
    for (size_t f = 0; f < boxes.size(); ++f) {
      boxes[f] = face_box(vertices, mesh_faces, static_cast<int>(f));
      degenerate[f] = test.degenerate(static_cast<int>(f)) ? 1 : 0;
    }
    buckets = buckets_for(boxes);
    for (size_t f = 0; f < boxes.size(); ++f) buckets.insert(static_cast<int>(f), boxes[f]);
  }

  // Faces with a corner where `changed` differs from the stored pose, ascending.
  std::vector<int> moved_faces(const Eigen::Ref<const Eigen::MatrixX3d>& changed) const {
    std::vector<int> moved;
    for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
      if (changed(v, 0) == vertices(v, 0) && changed(v, 1) == vertices(v, 1) && changed(v, 2) == vertices(v, 2)) continue;
      for (int f : faces_of_vertex[static_cast<int>(v)]) moved.push_back(f);
    }
    std::sort(moved.begin(), moved.end());
    moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
    return moved;
  }

  // The pairs of `changed` that involve a face of `moved` (ascending).
  FacePairs pairs_of_moved(const Eigen::Ref<const Eigen::MatrixX3d>& changed, const std::vector<int>& moved) const {
    const detail::FacePairTest test(changed, *faces);
    std::vector<Box> moved_boxes(moved.size());
    std::vector<char> moved_degenerate(moved.size(), 0);
    for (size_t i = 0; i < moved.size(); ++i) {
      moved_boxes[i] = face_box(changed, *faces, moved[i]);
      moved_degenerate[i] = test.degenerate(moved[i]) ? 1 : 0;
    }
    // The moved faces among themselves, through buckets of their own new boxes (by position in `moved`).
    Buckets among_moved = buckets_for(moved_boxes);
    for (size_t i = 0; i < moved.size(); ++i) among_moved.insert(static_cast<int>(i), moved_boxes[i]);
    std::vector<char> is_moved(boxes.size(), 0);
    for (int f : moved) is_moved[static_cast<size_t>(f)] = 1;

    tbb::enumerable_thread_specific<FacePairs> found;
    const auto test_one = [&](size_t i) {
      const int f = moved[i];
      FacePairs& out = found.local();
      if (moved_degenerate[i] != 0) {
        out.emplace_back(f, f);
        return;
      }
      buckets.query(moved_boxes[i], [&](int g) {
        if (degenerate[static_cast<size_t>(g)] != 0 || is_moved[static_cast<size_t>(g)] != 0) return;
        if (test.intersect(f, g)) out.emplace_back(std::min(f, g), std::max(f, g));
      });
      among_moved.query(moved_boxes[i], [&](int j) {
        if (static_cast<size_t>(j) <= i || moved_degenerate[static_cast<size_t>(j)] != 0) return;
        if (test.intersect(f, moved[static_cast<size_t>(j)])) out.emplace_back(f, moved[static_cast<size_t>(j)]);
      });
    };
    if (moved.size() < kParallelFaces) {
      for (size_t i = 0; i < moved.size(); ++i) test_one(i);
    } else {
      tbb::parallel_for(size_t{0}, moved.size(), test_one);
    }
    FacePairs pairs;
    for (const FacePairs& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
    return pairs;
  }

  Eigen::MatrixX3d vertices;
  std::shared_ptr<const Eigen::MatrixX3i> faces;
  AdjacencyLists faces_of_vertex;
  std::vector<Box> boxes;
  std::vector<char> degenerate;
  Buckets buckets;
};

SelfIntersectionTracker::SelfIntersectionTracker(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces)
    : SelfIntersectionTracker(vertices, faces, self_intersecting_face_pairs(vertices, faces)) {}

SelfIntersectionTracker::SelfIntersectionTracker(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                                 FacePairs known_pairs)
    : pairs_(std::move(known_pairs)) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  detail::check_finite_vertices(vertices, "SelfIntersectionTracker");
  grid_ = std::make_unique<Grid>(vertices, std::make_shared<const Eigen::MatrixX3i>(faces));
  sort_unique(pairs_);
}

SelfIntersectionTracker::~SelfIntersectionTracker() = default;
SelfIntersectionTracker::SelfIntersectionTracker(const SelfIntersectionTracker& other)
    : grid_(std::make_unique<Grid>(*other.grid_)), pairs_(other.pairs_) {}
SelfIntersectionTracker& SelfIntersectionTracker::operator=(const SelfIntersectionTracker& other) {
  if (this != &other) {
    grid_ = std::make_unique<Grid>(*other.grid_);
    pairs_ = other.pairs_;
  }
  return *this;
}
SelfIntersectionTracker::SelfIntersectionTracker(SelfIntersectionTracker&&) noexcept = default;
SelfIntersectionTracker& SelfIntersectionTracker::operator=(SelfIntersectionTracker&&) noexcept = default;

const Eigen::MatrixX3d& SelfIntersectionTracker::vertices() const { return grid_->vertices; }
const Eigen::MatrixX3i& SelfIntersectionTracker::faces() const { return *grid_->faces; }

void SelfIntersectionTracker::check_pose(const Eigen::Ref<const Eigen::MatrixX3d>& changed) const {
  if (changed.rows() != grid_->vertices.rows()) {
    throw ArgumentError("SelfIntersectionTracker: a pose of " + std::to_string(changed.rows()) +
                        " vertices for a mesh of " + std::to_string(grid_->vertices.rows()));
  }
  detail::check_finite_vertices(changed, "SelfIntersectionTracker");
}

FacePairs SelfIntersectionTracker::pairs_if(const Eigen::Ref<const Eigen::MatrixX3d>& changed) const {
  check_pose(changed);
  const std::vector<int> moved = grid_->moved_faces(changed);
  if (moved.empty()) return pairs_;
  if (static_cast<double>(moved.size()) > kWholeTestFraction * static_cast<double>(grid_->boxes.size())) {
    return self_intersecting_face_pairs(changed, *grid_->faces);
  }
  FacePairs pairs;
  for (const auto& pair : pairs_) {
    if (!std::binary_search(moved.begin(), moved.end(), pair.first) &&
        !std::binary_search(moved.begin(), moved.end(), pair.second)) {
      pairs.push_back(pair);
    }
  }
  const FacePairs fresh = grid_->pairs_of_moved(changed, moved);
  pairs.insert(pairs.end(), fresh.begin(), fresh.end());
  sort_unique(pairs);
  return pairs;
}

void SelfIntersectionTracker::update(const Eigen::Ref<const Eigen::MatrixX3d>& changed) { update(changed,
    pairs_if(changed)); }

void SelfIntersectionTracker::update(const Eigen::Ref<const Eigen::MatrixX3d>& changed, FacePairs known) {
  check_pose(changed);
  FacePairs pairs = std::move(known);
  sort_unique(pairs);
  const std::vector<int> moved = grid_->moved_faces(changed);
  if (static_cast<double>(moved.size()) > kWholeTestFraction * static_cast<double>(grid_->boxes.size())) {
    grid_ = std::make_unique<Grid>(changed, grid_->faces);  // cells sized for the new pose
    pairs_ = std::move(pairs);
    return;
  }
  Grid& grid = *grid_;
  const detail::FacePairTest test(changed, *grid.faces);
  for (int f : moved) grid.buckets.erase(f, grid.boxes[static_cast<size_t>(f)]);
  grid.vertices = changed;
  for (int f : moved) {
    grid.boxes[static_cast<size_t>(f)] = face_box(changed, *grid.faces, f);
    grid.degenerate[static_cast<size_t>(f)] = test.degenerate(f) ? 1 : 0;
    grid.buckets.insert(f, grid.boxes[static_cast<size_t>(f)]);
  }
  pairs_ = std::move(pairs);
}

}  // namespace posekit
