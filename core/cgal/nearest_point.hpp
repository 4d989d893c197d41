// The point of a triangle nearest to a point, by CGAL's projection.
#pragma once

#include <Eigen/Core>

namespace posekit::detail {

/// The point of triangle (`a`, `b`, `c`) nearest to `point`.
Eigen::RowVector3d nearest_point_on_triangle(const Eigen::RowVector3d& point, const Eigen::RowVector3d& a,
                                             const Eigen::RowVector3d& b, const Eigen::RowVector3d& c);

}  // namespace posekit::detail
