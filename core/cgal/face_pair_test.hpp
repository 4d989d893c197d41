// The exact test of two faces of one mesh for intersection, by the rules of
// CGAL::Polygon_mesh_processing::self_intersections (see posekit/self_intersections.hpp), shared by
// the whole-mesh test, the tracker that re-tests only what moved, and the mesh checks.
#pragma once

#include <Eigen/Core>

namespace posekit::detail {

class FacePairTest {
 public:
  /// `vertices` (#V by 3) and `faces` (#F by 3, valid indices) must outlive the test.
  FacePairTest(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces)
      : vertices_(vertices), faces_(faces) {}

  /// Whether face `f` is degenerate: its corners collinear or repeated.
  bool degenerate(int f) const;
  /// Whether the non-degenerate faces `f` and `g` intersect. Faces sharing a vertex or an edge (by
  /// index) intersect only beyond it, as CGAL::Polygon_mesh_processing::internal::do_faces_intersect
  /// decides with halfedge adjacency.
  bool intersect(int f, int g) const;

 private:
  const Eigen::Ref<const Eigen::MatrixX3d> vertices_;
  const Eigen::Ref<const Eigen::MatrixX3i> faces_;
};

}  // namespace posekit::detail
