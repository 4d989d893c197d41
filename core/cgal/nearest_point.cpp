#include "cgal/nearest_point.hpp"

#include "cgal/kernel.hpp"

namespace posekit::detail {
namespace {

ExactPoint exact(const Eigen::RowVector3d& point) { return {point(0), point(1), point(2)}; }

}  // namespace

Eigen::RowVector3d nearest_point_on_triangle(const Eigen::RowVector3d& point, const Eigen::RowVector3d& a,
                                             const Eigen::RowVector3d& b, const Eigen::RowVector3d& c) {
  const auto project = ExactKernel().construct_projected_point_3_object();
  const ExactPoint nearest = project(ExactKernel::Triangle_3(exact(a), exact(b), exact(c)), exact(point));
  return {nearest.x(), nearest.y(), nearest.z()};
}

}  // namespace posekit::detail
