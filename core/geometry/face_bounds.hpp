// The axis-aligned bounds of one face, shared by the whole-mesh self-intersection test and the
// tracker that re-tests what moved.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>

namespace posekit::detail {

struct FaceBounds {
  std::array<double, 3> lower{};
  std::array<double, 3> upper{};
};

/// The bounds of face `f` of the #F by 3 `faces` on the #V by 3 `vertices`.
inline FaceBounds face_bounds(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces, Eigen::Index f) {
  FaceBounds bounds;
  for (int axis = 0; axis < 3; ++axis) {
    const double a = vertices(faces(f, 0), axis);
    const double b = vertices(faces(f, 1), axis);
    const double c = vertices(faces(f, 2), axis);
    bounds.lower[static_cast<std::size_t>(axis)] = std::min({a, b, c});
    bounds.upper[static_cast<std::size_t>(axis)] = std::max({a, b, c});
  }
  return bounds;
}

}  // namespace posekit::detail
