#include "geometry/face_pair_test.hpp"
#include "geometry/vertex_checks.hpp"

#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <vector>

namespace posekit {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using FacePair = std::pair<int, int>;
using detail::FacePairTest;

// Bounding box of one face; its id is the face index, so boxes may be copied freely by the
// (parallel) box intersection, and no global counter is touched (safe when several meshes are
// checked at once).
class FaceBox {
 public:
  using NT = double;
  using ID = std::size_t;

  FaceBox() = default;
  FaceBox(const CGAL::Bbox_3& box, int face) : box_(box), face_(face) {}
  static int dimension() { return 3; }
  double min_coord(int axis) const { return box_.min(axis); }
  double max_coord(int axis) const { return box_.max(axis); }
  ID id() const { return static_cast<ID>(face_); }
  int face() const { return face_; }

 private:
  CGAL::Bbox_3 box_;
  int face_ = -1;
};

// CGAL's parallel box intersection works on four copies of the boxes in sixteen tasks; it only pays
// off with more than a couple of cores and more than a few thousand faces (measured on an 84k-face mesh:
// with 2 cores the sequential search is about 10% faster).
constexpr std::size_t kParallelBoxThreshold = 4096;
constexpr int kParallelBoxMinThreads = 4;
// Boxes per leaf of CGAL's segment tree below which it scans pairs directly; 1000 was fastest on
// an 84k-face mesh; with the library's default of 10 the whole search takes 2.5 times longer.
constexpr std::ptrdiff_t kBoxCutoff = 1000;

std::vector<FacePair> candidate_pairs(std::vector<FaceBox>& boxes) {
  tbb::enumerable_thread_specific<std::vector<FacePair>> found;
  auto collect = [&found](const FaceBox& a, const FaceBox& b) {
    found.local().emplace_back(std::min(a.face(), b.face()), std::max(a.face(), b.face()));
  };
  if (boxes.size() >= kParallelBoxThreshold &&
      tbb::this_task_arena::max_concurrency() >= kParallelBoxMinThreads) {
    CGAL::box_self_intersection_d<CGAL::Parallel_tag>(boxes.begin(), boxes.end(), collect, kBoxCutoff);
  } else {
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), collect, kBoxCutoff);
  }
  std::vector<FacePair> all;
  std::size_t total = 0;
  for (const auto& part : found) total += part.size();
  all.reserve(total);
  for (const auto& part : found) all.insert(all.end(), part.begin(), part.end());
  return all;
}

}  // namespace

std::vector<FacePair> self_intersecting_face_pairs(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                                   const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  detail::check_finite_vertices(vertices, "self_intersecting_faces");

  std::vector<Point> points;
  points.reserve(static_cast<size_t>(vertices.rows()));
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) points.emplace_back(vertices(v, 0), vertices(v, 1), vertices(v, 2));

  // Degenerate faces are reported on their own and left out of the pair tests, as CGAL does: the
  // triangle predicates are undefined for them.
  std::vector<FacePair> result;
  std::vector<FaceBox> boxes;
  boxes.reserve(static_cast<size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Point& p = points[static_cast<size_t>(faces(f, 0))];
    const Point& q = points[static_cast<size_t>(faces(f, 1))];
    const Point& r = points[static_cast<size_t>(faces(f, 2))];
    if (CGAL::collinear(p, q, r)) {
      result.emplace_back(static_cast<int>(f), static_cast<int>(f));
    } else {
      boxes.emplace_back(p.bbox() + q.bbox() + r.bbox(), static_cast<int>(f));
    }
  }

  const std::vector<FacePair> candidates = candidate_pairs(boxes);
  std::vector<unsigned char> hit(candidates.size(), 0);
  const FacePairTest test(vertices, faces);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        hit[i] = test.intersect(candidates[i].first, candidates[i].second) ? 1 : 0;
                      }
                    });
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (hit[i] != 0) result.push_back(candidates[i]);
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

std::vector<int> faces_in_pairs(const std::vector<std::pair<int, int>>& pairs) {
  std::vector<int> result;
  for (const auto& [f, g] : pairs) {
    result.push_back(f);
    result.push_back(g);
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

std::vector<int> self_intersecting_faces(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  return faces_in_pairs(self_intersecting_face_pairs(vertices, faces));
}

std::vector<int> new_intersecting_faces(const std::vector<int>& mesh_faces, const std::vector<int>& reference_faces) {
  std::vector<int> mesh = mesh_faces;
  std::vector<int> reference = reference_faces;
  std::sort(mesh.begin(), mesh.end());
  mesh.erase(std::unique(mesh.begin(), mesh.end()), mesh.end());
  std::sort(reference.begin(), reference.end());
  std::vector<int> result;
  std::set_difference(mesh.begin(), mesh.end(), reference.begin(), reference.end(), std::back_inserter(result));
  return result;
}

}  // namespace posekit
