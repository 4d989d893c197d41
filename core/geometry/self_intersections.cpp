#include "cgal/face_pair_test.hpp"
#include "geometry/box_overlaps.hpp"
#include "geometry/face_bounds.hpp"
#include "geometry/vertex_checks.hpp"

#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <vector>

namespace posekit {
namespace {

using FacePair = std::pair<int, int>;
using detail::FacePairTest;

}  // namespace

std::vector<FacePair> self_intersecting_face_pairs(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                                   const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  detail::check_finite_vertices(vertices, "self_intersecting_faces");

  // Degenerate faces are reported on their own and left out of the pair tests, as CGAL does: the
  // triangle predicates are undefined for them.
  const FacePairTest test(vertices, faces);
  std::vector<FacePair> result;
  std::vector<detail::ItemBox> boxes;
  boxes.reserve(static_cast<size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (test.degenerate(static_cast<int>(f))) {
      result.emplace_back(static_cast<int>(f), static_cast<int>(f));
    } else {
      const detail::FaceBounds bounds = detail::face_bounds(vertices, faces, f);
      boxes.push_back({bounds.lower, bounds.upper, static_cast<int>(f)});
    }
  }

  const std::vector<FacePair> candidates = detail::overlapping_box_pairs(boxes);
  std::vector<unsigned char> hit(candidates.size(), 0);
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
