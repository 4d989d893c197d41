// Edge-space refinement of a stitched mixed-space shape: Gauss-Newton over the positions of the
// vertices that only joints hold and one rigid motion per rigid piece, on the joints' edge lengths and
// dihedral angles. Rigid pieces stay rigid; joints bend so that, together, they best match their
// interpolated targets, which no alignment of independently reconstructed joints can guarantee
// (a joint reconstructed alone drifts; one rigid motion cannot fit all of its attachments).
#pragma once

#include "interpolate/block_sparse_matrix.hpp"
#include "interpolate/edge_space_patch.hpp"
#include "interpolate/joint_layout.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include <vector>

namespace posekit::interpolation {

struct ArticulatedStats {
  int iterations = 0;
  double initial_energy = 0.0;
  double final_energy = 0.0;
};

class ArticulatedRefinement {
 public:
  /// `joints`: the joint patches (their edges and hinges make the energy); `pieces`: the rigid pieces;
  /// `vertex_count` vertices in the mesh.
  ArticulatedRefinement(const std::vector<const EdgeSpacePatch*>& joints, const std::vector<MeshComponent>& pieces,
                        int vertex_count);

  /// Refines the #V by 3 `x` in place for the #E target `lengths` and `angles` (radians, mesh edges),
  /// with dihedral errors weighted by `bending_weight`, for at most `iterations` Gauss-Newton steps
  /// (stopping when one lowers the energy by less than `tolerance` of it).
  ArticulatedStats refine(Eigen::MatrixX3d& x, const Eigen::VectorXd& lengths, const Eigen::VectorXd& angles,
                          double bending_weight, int iterations, double tolerance);

  double energy(const Eigen::Ref<const Eigen::MatrixX3d>& x, const Eigen::VectorXd& lengths,
                const Eigen::VectorXd& angles,
                double bending_weight) const;

 private:
  using Solver = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;
  struct Element {
    int edge = -1;    // mesh edge whose target applies
    int corners = 2;  // 2 for an edge (a, b), 4 for a hinge (a, b, c, d)
    Hinge hinge;      // mesh vertex indices
    int node_count = 0;
    int nodes[8] = {};
    int slot_offset = 0;  // node_count^2 slots from here
  };
  std::vector<Element> elements_;
  std::vector<BlockSparseMatrix3::Slot> slots_;
  std::vector<int> free_node_;   // per vertex: its node, or -1 when a piece holds it
  std::vector<int> piece_of_;    // per vertex: its piece, or -1
  std::vector<int> piece_node_;  // per piece: its translation node (rotation node = + 1), or -1 without joint
  std::vector<std::vector<int>> piece_vertices_;
  int node_count_ = 0;
  BlockSparseMatrix3 normal_matrix_;
  Solver solver_;
};

}  // namespace posekit::interpolation
