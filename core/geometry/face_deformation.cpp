#include <posekit/error.hpp>
#include <posekit/face_deformation.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

namespace posekit {

Eigen::Matrix3d face_basis(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a;
  const Eigen::Vector3d e2 = c - a;
  const Eigen::Vector3d cross = e1.cross(e2);
  const double norm = cross.norm();
  Eigen::Matrix3d basis;
  basis.col(0) = e1;
  basis.col(1) = e2;
  basis.col(2) = norm > 0.0 ? Eigen::Vector3d(cross / std::sqrt(norm)) : Eigen::Vector3d::Zero();
  return basis;
}

std::vector<Eigen::Matrix3d> face_deformation_gradients(const Eigen::Ref<const Eigen::MatrixX3d>& source,
                                                        const Eigen::Ref<const Eigen::MatrixX3d>& target,
                                                        const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  if (source.rows() != target.rows()) {
    throw ArgumentError("face_deformation_gradients: source has " + std::to_string(source.rows()) +
                        " vertices but target has " + std::to_string(target.rows()));
  }
  check_face_indices(faces, static_cast<int>(source.rows()));
  const int face_count = static_cast<int>(faces.rows());
  std::vector<Eigen::Matrix3d> gradients(static_cast<size_t>(face_count), Eigen::Matrix3d::Identity());
  tbb::parallel_for(0, face_count, [&](int f) {
    const Eigen::Vector3d a = source.row(faces(f, 0));
    const Eigen::Vector3d b = source.row(faces(f, 1));
    const Eigen::Vector3d c = source.row(faces(f, 2));
    if ((b - a).cross(c - a).norm() <= 0.0) return;
    const Eigen::Matrix3d target_basis =
        face_basis(target.row(faces(f, 0)), target.row(faces(f, 1)), target.row(faces(f, 2)));
    gradients[static_cast<size_t>(f)] = target_basis * face_basis(a, b, c).inverse();
  });
  return gradients;
}

}  // namespace posekit
