#include "cgal/nearest_point.hpp"

#include "cgal/kernel.hpp"

namespace posekit::detail {

Eigen::RowVector3d nearest_point_on_triangle(const Eigen::RowVector3d& point, const Eigen::RowVector3d& a,
                                             const Eigen::RowVector3d& b, const Eigen::RowVector3d& c) {
  const auto project = ExactKernel().construct_projected_point_3_object();
  const ExactKernel::Triangle_3 triangle(exact_point(a), exact_point(b), exact_point(c));
  const ExactPoint nearest = project(triangle, exact_point(point));
  return {nearest.x(), nearest.y(), nearest.z()};
}

}  // namespace posekit::detail
