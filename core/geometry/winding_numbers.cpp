#include <posekit/winding_numbers.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <cmath>

namespace posekit {
namespace {

// Van Oosterom and Strackee's formula for the solid angle of a triangle seen from `point`.
double solid_angle(const Eigen::RowVector3d& point, const Eigen::RowVector3d& a, const Eigen::RowVector3d& b,
                   const Eigen::RowVector3d& c) {
  const Eigen::Vector3d u = (a - point).transpose();
  const Eigen::Vector3d v = (b - point).transpose();
  const Eigen::Vector3d w = (c - point).transpose();
  const double lu = u.norm();
  const double lv = v.norm();
  const double lw = w.norm();
  // A corner of the triangle itself: the triangle is seen edge on.
  if (lu == 0.0 || lv == 0.0 || lw == 0.0) return 0.0;
  const double numerator = u.dot(v.cross(w));
  const double denominator = lu * lv * lw + u.dot(v) * lw + v.dot(w) * lu + w.dot(u) * lv;
  return 2.0 * std::atan2(numerator, denominator);
}

}  // namespace

Eigen::VectorXd winding_numbers(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                const Eigen::MatrixX3d& points) {
  Eigen::VectorXd winding(points.rows());
  tbb::parallel_for(Eigen::Index{0}, points.rows(), [&](Eigen::Index p) {
    double sum = 0.0;
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      sum += solid_angle(points.row(p), vertices.row(faces(f, 0)), vertices.row(faces(f, 1)), vertices.row(faces(f, 2)));
    }
    winding(p) = sum / (4.0 * M_PI);
  });
  return winding;
}

}  // namespace posekit
