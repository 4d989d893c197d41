// Projection from edge space back to positions: the mesh (patch) whose edge lengths and dihedral
// angles best match given targets. The start is the gradient-space interpolation of the patch (per
// face, the blend of the rotation vectors and stretches from pose 0 to every pose; positions by one
// Poisson solve against a matrix factorized once), which keeps large rotations and 180-degree twists.
// Gauss-Newton then minimizes
//   sum_edges ((|e| - l*) / l*)^2 + bending_weight * sum_hinges (theta - theta*)^2
// with a matrix whose pattern, and so the factorization's symbolic analysis, is fixed once.
#pragma once

#include "interpolate/block_sparse_matrix.hpp"
#include "interpolate/edge_space_patch.hpp"
#include "interpolate/pose_deformations.hpp"
#include "interpolate/sparse_cholesky.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include <vector>

namespace posekit::interpolation {

struct ReconstructionOptions {
  int max_iterations = 5;       ///< Gauss-Newton iterations (0: the gradient-space start only)
  double bending_weight = 0.1;  ///< weight of squared dihedral errors against squared relative length errors
  double tolerance = 1e-4;      ///< stop when an iteration lowers the energy by less than this fraction
};

struct ReconstructionStats {
  int iterations = 0;
  double initial_energy = 0.0;
  double final_energy = 0.0;
};

class EdgeSpaceReconstruction {
 public:
  /// Prepares the reconstruction of `patch` of a mesh whose pose 0 is `reference` (#V by 3) and whose
  /// faces deform as `deformations` says from pose 0 to the other poses.
  EdgeSpaceReconstruction(EdgeSpacePatch patch, const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                          const PoseDeformations& deformations);

  /// Local positions (patch vertices by 3) for target `lengths` (one per patch edge, > 0) and target
  /// `angles` (one per hinge, radians), both interpolated with the K pose `weights`. Not safe to call
  /// concurrently on one object.
  Eigen::MatrixX3d reconstruct(const Eigen::VectorXd& weights, const Eigen::VectorXd& lengths,
                               const Eigen::VectorXd& angles, const ReconstructionOptions& options,
                               ReconstructionStats* stats = nullptr);

  /// The gradient-space start alone, for the K pose `weights`.
  Eigen::MatrixX3d gradient_guess(const Eigen::VectorXd& weights) const;

  /// Gauss-Newton refinement of `x` in place; returns the statistics.
  ReconstructionStats refine(Eigen::MatrixX3d& x, const Eigen::VectorXd& lengths, const Eigen::VectorXd& angles,
                             const ReconstructionOptions& options);

  /// The energy above at the local positions `x`.
  double energy(const Eigen::Ref<const Eigen::MatrixX3d>& x, const Eigen::VectorXd& lengths,
                const Eigen::VectorXd& angles,
                double bending_weight) const;

  const EdgeSpacePatch& patch() const { return patch_; }

 private:
  using Solver = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;
  // Per face: pose-0 hat-function gradients, area, and the gradients of the pose-0 coordinates.
  struct FaceGradient {
    Eigen::Matrix3d hat_gradients = Eigen::Matrix3d::Zero();  // column i: gradient of corner i's hat function
    Eigen::Matrix3d coordinates = Eigen::Matrix3d::Zero();    // column c: gradient of coordinate c
    double area = 0.0;
  };

  EdgeSpacePatch patch_;
  std::vector<FaceGradient> gradients_;
  std::vector<std::vector<Eigen::Vector3d>> logs_;       // [k - 1][local face]
  std::vector<std::vector<Eigen::Matrix3d>> stretches_;  // [k - 1][local face]
  Solver gradient_solver_;
  void prepare_gauss_newton();  // builds the pattern below on first use
  bool gauss_newton_ready_ = false;
  BlockSparseMatrix3 normal_matrix_;                   // Gauss-Newton: one 3 x 3 block per vertex
  std::vector<BlockSparseMatrix3::Slot> edge_slots_;   // per edge: (a, b), (b, a)
  std::vector<BlockSparseMatrix3::Slot> hinge_slots_;  // per hinge: 16 blocks of (a, b, c, d) x (a, b, c, d)
  SparseCholesky normal_solver_;
};

}  // namespace posekit::interpolation
