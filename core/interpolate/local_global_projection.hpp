// The last step of the mixed-space projection: local/global passes over the whole mesh towards the
// interpolated edge lengths and dihedral angles. Locally, every edge asks for its current direction
// at its interpolated length, and every hinge asks for its two wings turned about the hinge edge by
// half the angle it is off each (the wing edges' directions, again at their interpolated lengths);
// globally, positions by least squares on all these edge vectors. The matrix is a weighted graph
// Laplacian that depends on the connectivity only: factorized once, each pass costs one solve. The
// passes are a fixed-point iteration, sped up by Anderson acceleration (mixing the last few passes).
// Parts that are not quite rigid come out of vertex interpolation slightly shrunk and bent; these
// passes give their edges back their lengths and their hinges their angles.
#pragma once

#include "interpolate/edge_space_patch.hpp"

#include <posekit/topology.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include <array>
#include <vector>

namespace posekit::interpolation {

class LocalGlobalProjection {
 public:
  /// For the mesh with #F by 3 `faces` and `vertex_count` vertices, `edges` = edge_map(faces),
  /// `incident_faces` = edge_faces(edges), the #E `hinge` flags and #E `reference_lengths` (> 0; every
  /// edge vector is weighed by one over its squared reference length, so errors count relatively and
  /// small features keep their shape); hinges weigh `hinge_weight` (>= 0) against an edge's own length.
  LocalGlobalProjection(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count, const EdgeMap& edges,
                        const AdjacencyLists& incident_faces, const std::vector<char>& hinge,
                        const Eigen::VectorXd& reference_lengths, double hinge_weight);

  /// `passes` rounds on the #V by 3 `x`, in place, towards the #E target `lengths` and `angles`.
  void project(Eigen::MatrixX3d& x, const Eigen::VectorXd& lengths, const Eigen::VectorXd& angles, int passes) const;

 private:
  struct MeshHinge {
    Hinge corners;                 // mesh vertices
    int edge = -1;                 // mesh edge
    std::array<int, 4> wings{};    // mesh edges (a, c), (b, c), (a, d), (b, d)
  };
  Eigen::MatrixX2i edges_;
  std::vector<MeshHinge> hinges_;
  Eigen::VectorXd relative_;  // per edge: one over its squared reference length
  AdjacencyLists wing_roles_;      // per edge: 4 * hinge + wing for every hinge it is a wing of
  AdjacencyLists vertex_edges_;    // per vertex: its edges
  double hinge_weight_ = 0.0;
  double anchor_ = 0.0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
};

}  // namespace posekit::interpolation
