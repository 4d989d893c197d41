// The rotation closest to a 3 by 3 matrix: the local step of every as-rigid-as-possible solver.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

namespace posekit::detail {

/// The rotation R maximizing <R, m> (trace of R^T m): U diag(1, 1, det(U V^T)) V^T from m = U S V^T.
inline Eigen::Matrix3d closest_rotation_svd(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0.0) u.col(2) *= -1.0;
  return u * v.transpose();
}

/// The same, faster: the polar factor m (m^T m)^-1/2 from the closed-form eigendecomposition of the
/// symmetric m^T m; falls back to the SVD when m is nearly singular or reflects.
inline Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& m) {
  if (m.determinant() > 0.0) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(m.transpose() * m);
    const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
    if (values(0) > 1e-12 * values(2) && values(2) > 0.0) {
      const Eigen::Matrix3d& v = eigen.eigenvectors();
      const Eigen::Matrix3d r = m * v * values.cwiseSqrt().cwiseInverse().asDiagonal() * v.transpose();
      // computeDirect loses accuracy for clustered eigenvalues; keep the result only if it is a rotation.
      if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9) return r;
    }
  }
  return closest_rotation_svd(m);
}

}  // namespace posekit::detail
