// The exact test of two faces of one mesh for intersection, by the rules of
// CGAL::Polygon_mesh_processing::self_intersections (see posekit/self_intersections.hpp), shared by
// the whole-mesh test and the tracker that re-tests only what moved.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <Eigen/Core>

#include <array>
#include <vector>

namespace posekit::detail {

using IntersectionKernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// Same rules as CGAL::Polygon_mesh_processing::internal::do_faces_intersect, with shared vertices
// and edges recognized by vertex index instead of halfedge adjacency.
class FacePairTest {
 public:
  using Point = IntersectionKernel::Point_3;
  using Segment = IntersectionKernel::Segment_3;
  using Triangle = IntersectionKernel::Triangle_3;

  /// `vertices` (#V by 3) and `faces` (#F by 3) must outlive the test.
  FacePairTest(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
               const Eigen::Ref<const Eigen::MatrixX3i>& faces) : vertices_(vertices), faces_(faces) {}

  /// Whether face `f` is degenerate: its corners collinear or repeated.
  bool degenerate(int f) const {
    const std::array<int, 3> c = corners(f);
    return CGAL::collinear(point(c[0]), point(c[1]), point(c[2]));
  }

  /// Whether the non-degenerate faces `f` and `g` intersect.

  bool intersect(int f, int g) const {
    const std::array<int, 3> a = corners(f);
    const std::array<int, 3> b = corners(g);
    int shared_count = 0;
    int first_shared_in_a = -1;
    int first_shared_in_b = -1;
    std::array<bool, 3> a_shared{false, false, false};
    std::array<bool, 3> b_shared{false, false, false};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (a[i] != b[j] || a_shared[i] || b_shared[j]) continue;
        a_shared[i] = b_shared[j] = true;
        if (shared_count++ == 0) {
          first_shared_in_a = i;
          first_shared_in_b = j;
        }
      }
    }

    if (shared_count >= 3) return true;  // the same triangle twice
    if (shared_count == 2) {
      // Sharing an edge: they overlap only when folded flat onto each other, i.e. the two opposite
      // corners are coplanar with the edge and on the same side of it.
      const int a_apex = unshared_corner(a_shared);
      const int b_apex = unshared_corner(b_shared);
      const Point p = point(a[(a_apex + 1) % 3]);
      const Point q = point(a[(a_apex + 2) % 3]);
      const Point r = point(a[a_apex]);
      const Point s = point(b[b_apex]);
      return CGAL::coplanar(p, q, r, s) && CGAL::coplanar_orientation(p, q, r, s) == CGAL::POSITIVE;
    }
    const Triangle ta = triangle(a);
    const Triangle tb = triangle(b);
    if (shared_count == 1) {
      // Sharing one vertex: any further contact shows up on an edge opposite the shared vertex.
      const Segment a_opposite(point(a[(first_shared_in_a + 1) % 3]), point(a[(first_shared_in_a + 2) % 3]));
      const Segment b_opposite(point(b[(first_shared_in_b + 1) % 3]), point(b[(first_shared_in_b + 2) % 3]));
      return CGAL::do_intersect(ta, b_opposite) || CGAL::do_intersect(tb, a_opposite);
    }
    return CGAL::do_intersect(ta, tb);
  }

 private:
  std::array<int, 3> corners(int f) const { return {faces_(f, 0), faces_(f, 1), faces_(f, 2)}; }
  Point point(int vertex) const { return {vertices_(vertex, 0), vertices_(vertex, 1), vertices_(vertex, 2)}; }
  Triangle triangle(const std::array<int, 3>& c) const { return {point(c[0]), point(c[1]), point(c[2])}; }
  static int unshared_corner(const std::array<bool, 3>& shared) {
    return !shared[0] ? 0 : (!shared[1] ? 1 : 2);
  }

  const Eigen::Ref<const Eigen::MatrixX3d> vertices_;
  const Eigen::Ref<const Eigen::MatrixX3i> faces_;
};

}  // namespace posekit::detail
