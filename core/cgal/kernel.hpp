// The one CGAL kernel posekit uses: exact predicates on double coordinates, inexact constructions.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <Eigen/Core>

namespace posekit::detail {

using ExactKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactPoint = ExactKernel::Point_3;

/// Row `row` of a #V by 3 matrix as a CGAL point.
inline ExactPoint exact_point(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, Eigen::Index row) {
  return {vertices(row, 0), vertices(row, 1), vertices(row, 2)};
}

/// A row vector as a CGAL point.
inline ExactPoint exact_point(const Eigen::RowVector3d& point) { return {point(0), point(1), point(2)}; }

}  // namespace posekit::detail
