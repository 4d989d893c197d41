#include <posekit/geometry.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Geometry>

namespace posekit {
namespace {

// Cross product of two edge vectors of face f: twice the area times the unit normal.
Eigen::RowVector3d area_vector(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                               const Eigen::Ref<const Eigen::MatrixX3i>& faces, Eigen::Index f) {
  const Eigen::RowVector3d a = vertices.row(faces(f, 0));
  const Eigen::RowVector3d b = vertices.row(faces(f, 1));
  const Eigen::RowVector3d c = vertices.row(faces(f, 2));
  return (b - a).cross(c - a);
}

}  // namespace

Eigen::MatrixX3d face_normals(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  Eigen::MatrixX3d normals(faces.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVector3d n = area_vector(vertices, faces, f);
    const double length = n.norm();
    // Zero for degenerate faces rather than NaN, so sums over faces stay meaningful.
    normals.row(f) = length > 0.0 ? Eigen::RowVector3d(n / length) : Eigen::RowVector3d::Zero();
  }
  return normals;
}

Eigen::VectorXd face_areas(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                           const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  Eigen::VectorXd areas(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) areas(f) = 0.5 * area_vector(vertices, faces, f).norm();
  return areas;
}

Eigen::MatrixX3d vertex_normals(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(vertices.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVector3d n = area_vector(vertices, faces, f);
    for (int corner = 0; corner < 3; ++corner) normals.row(faces(f, corner)) += n;
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v) {
    const double length = normals.row(v).norm();
    if (length > 0.0) normals.row(v) /= length;
  }
  return normals;
}

}  // namespace posekit
