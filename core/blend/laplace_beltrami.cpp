#include <posekit/error.hpp>
#include <posekit/laplace_beltrami.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <string>
#include <vector>

namespace posekit {
namespace {

// Faces this much smaller than the mean have cotangents that swamp the whole operator.
constexpr double kDegenerateAreaRatio = 1e-12;

double face_area(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                 Eigen::Index f) {
  const Eigen::RowVector3d a = vertices.row(faces(f, 0));
  const Eigen::RowVector3d b = vertices.row(faces(f, 1));
  const Eigen::RowVector3d c = vertices.row(faces(f, 2));
  return 0.5 * (b - a).cross(c - a).norm();
}

}  // namespace

void check_laplace_beltrami_mesh(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const int vertex_count = static_cast<int>(vertices.rows());
  if (vertex_count < 3 || faces.rows() == 0) {
    throw ArgumentError("the mesh has " + std::to_string(vertex_count) + " vertices and " +
                        std::to_string(faces.rows()) + " faces; at least one triangle is needed");
  }
  if (!vertices.allFinite()) throw ArgumentError("the mesh has a non-finite vertex coordinate");
  check_face_indices(faces, vertex_count);
  std::vector<char> used(static_cast<size_t>(vertex_count), 0);
  Eigen::VectorXd areas(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    areas(f) = face_area(vertices, faces, f);
    for (int corner = 0; corner < 3; ++corner) used[static_cast<size_t>(faces(f, corner))] = 1;
  }
  for (int v = 0; v < vertex_count; ++v) {
    if (!used[static_cast<size_t>(v)]) {
      throw ArgumentError("the mesh is degenerate: vertex " + std::to_string(v) + " is in no face");
    }
  }
  const double mean = areas.mean();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (!(areas(f) > kDegenerateAreaRatio * mean)) {
      throw ArgumentError("the mesh is degenerate: face " + std::to_string(f) + " (vertices " +
                          std::to_string(faces(f, 0)) + ", " + std::to_string(faces(f, 1)) + ", " +
                          std::to_string(faces(f, 2)) + ") has zero area");
    }
  }
}

Eigen::SparseMatrix<double> cotangent_laplacian(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                                const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const int vertex_count = static_cast<int>(vertices.rows());
  check_face_indices(faces, vertex_count);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(faces.rows()) * 12);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const int o = faces(f, corner);
      const int i = faces(f, (corner + 1) % 3);
      const int j = faces(f, (corner + 2) % 3);
      const Eigen::RowVector3d u = vertices.row(i) - vertices.row(o);
      const Eigen::RowVector3d v = vertices.row(j) - vertices.row(o);
      const double cross = u.cross(v).norm();
      if (!(cross > 0.0)) continue;  // a zero-area face contributes nothing rather than infinity
      const double half_cot = 0.5 * u.dot(v) / cross;
      entries.emplace_back(i, j, -half_cot);
      entries.emplace_back(j, i, -half_cot);
      entries.emplace_back(i, i, half_cot);
      entries.emplace_back(j, j, half_cot);
    }
  }
  Eigen::SparseMatrix<double> laplacian(vertex_count, vertex_count);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  return laplacian;
}

Eigen::VectorXd lumped_mass(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                            const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(vertices.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const double third = face_area(vertices, faces, f) / 3.0;
    for (int corner = 0; corner < 3; ++corner) mass(faces(f, corner)) += third;
  }
  return mass;
}

Eigen::MatrixXd weight_smoothness(const Eigen::SparseMatrix<double>& laplacian, const Eigen::VectorXd& mass,
                                  const Eigen::MatrixXd& weights) {
  if (laplacian.rows() != weights.rows() || mass.size() != weights.rows()) {
    throw ArgumentError("weight_smoothness: the weights have " + std::to_string(weights.rows()) +
                        " rows for a mesh of " + std::to_string(mass.size()) + " vertices");
  }
  const Eigen::MatrixXd stiff = laplacian * weights;
  return stiff.transpose() * mass.cwiseInverse().asDiagonal() * stiff;
}

}  // namespace posekit
