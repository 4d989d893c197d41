#include "cgal/face_pair_test.hpp"

#include "cgal/kernel.hpp"

#include <CGAL/intersections.h>

#include <algorithm>
#include <array>

namespace posekit::detail {
namespace {

using Segment = ExactKernel::Segment_3;
using Triangle = ExactKernel::Triangle_3;

std::array<int, 3> corners(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int f) {
  return {faces(f, 0), faces(f, 1), faces(f, 2)};
}

int unshared_corner(const std::array<bool, 3>& shared) { return !shared[0] ? 0 : (!shared[1] ? 1 : 2); }

}  // namespace

bool FacePairTest::degenerate(int f) const {
  const std::array<int, 3> c = corners(faces_, f);
  return CGAL::collinear(exact_point(vertices_, c[0]), exact_point(vertices_, c[1]), exact_point(vertices_, c[2]));
}

bool FacePairTest::intersect(int f, int g) const {
  const std::array<int, 3> a = corners(faces_, f);
  const std::array<int, 3> b = corners(faces_, g);
  const auto point = [&](int vertex) { return exact_point(vertices_, vertex); };
  const auto triangle = [&](const std::array<int, 3>& c) { return Triangle(point(c[0]), point(c[1]), point(c[2])); };
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
    const ExactPoint p = point(a[(a_apex + 1) % 3]);
    const ExactPoint q = point(a[(a_apex + 2) % 3]);
    const ExactPoint r = point(a[a_apex]);
    const ExactPoint s = point(b[b_apex]);
    return CGAL::coplanar(p, q, r, s) && CGAL::coplanar_orientation(p, q, r, s) == CGAL::POSITIVE;
  }
  if (shared_count == 1) {
    // Sharing one vertex: any further contact shows up on an edge opposite the shared vertex.
    const ExactPoint shared = point(a[first_shared_in_a]);
    const ExactPoint a1 = point(a[(first_shared_in_a + 1) % 3]);
    const ExactPoint a2 = point(a[(first_shared_in_a + 2) % 3]);
    const ExactPoint b1 = point(b[(first_shared_in_b + 1) % 3]);
    const ExactPoint b2 = point(b[(first_shared_in_b + 2) % 3]);
    // An opposite edge outside the other face's box, or strictly on one side of its plane, cannot
    // meet that face. The boxes decide nine in ten of a mesh's vertex-sharing pairs and the four
    // exact orientations most of the rest, before the triangle-segment tests, with their answer.
    // Edge st and face pqr.
    const auto edge_misses_face = [](const ExactPoint& p, const ExactPoint& q, const ExactPoint& r,
                                     const ExactPoint& s, const ExactPoint& t) {
      for (int axis = 0; axis < 3; ++axis) {
        if (std::max(s[axis], t[axis]) < std::min({p[axis], q[axis], r[axis]}) ||
            std::min(s[axis], t[axis]) > std::max({p[axis], q[axis], r[axis]})) {
          return true;
        }
      }
      const CGAL::Orientation side = CGAL::orientation(p, q, r, s);
      return side != CGAL::COPLANAR && side == CGAL::orientation(p, q, r, t);
    };
    const bool b_edge_misses = edge_misses_face(shared, a1, a2, b1, b2);
    const bool a_edge_misses = edge_misses_face(shared, b1, b2, a1, a2);
    return (!b_edge_misses && CGAL::do_intersect(Triangle(shared, a1, a2), Segment(b1, b2))) ||
           (!a_edge_misses && CGAL::do_intersect(Triangle(shared, b1, b2), Segment(a1, a2)));
  }
  return CGAL::do_intersect(triangle(a), triangle(b));
}

}  // namespace posekit::detail
