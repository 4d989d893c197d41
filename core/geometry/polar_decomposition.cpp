#include <posekit/rigid_motion.hpp>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace posekit {

PolarDecomposition polar_decomposition(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d singular = svd.singularValues();
  Eigen::Matrix3d u = svd.matrixU();
  // A reflection goes into the stretch, along the direction of the smallest singular value.
  if ((u * svd.matrixV().transpose()).determinant() < 0.0) {
    u.col(2) *= -1.0;
    singular(2) *= -1.0;
  }
  PolarDecomposition result;
  result.rotation = u * svd.matrixV().transpose();
  result.stretch = svd.matrixV() * singular.asDiagonal() * svd.matrixV().transpose();
  return result;
}

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m) { return polar_decomposition(m).rotation; }

}  // namespace posekit
