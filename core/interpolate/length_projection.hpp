// The last step of the mixed-space projection: least squares on all edge vectors, each kept in its
// direction and scaled to its interpolated length (the stitching rule of Winkler et al. applied to
// every edge). Parts that are not quite rigid come out of vertex interpolation slightly shrunk; this
// gives their edges back their lengths. The matrix is the graph Laplacian, factorized once.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

namespace posekit::interpolation {

class LengthProjection {
 public:
  /// For the #E by 2 `edges` of a mesh with `vertex_count` vertices.
  LengthProjection(const Eigen::MatrixX2i& edges, int vertex_count);

  /// `passes` rounds on the #V by 3 `x`, in place, towards the #E target `lengths`.
  void project(Eigen::MatrixX3d& x, const Eigen::VectorXd& lengths, int passes) const;

 private:
  Eigen::MatrixX2i edges_;
  double anchor_ = 0.0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace posekit::interpolation
