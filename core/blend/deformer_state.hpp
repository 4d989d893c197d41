// The precomputed state that the parts of BlendedDeformer share (construction, constraints,
// iterations, interpolation).
#pragma once

#include <posekit/blend_dictionary.hpp>
#include <posekit/blended_deformation.hpp>

#include "blend/dictionary_product.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <memory>
#include <vector>

namespace posekit {

struct BlendedDeformer::State {
  BlendOptions options;
  BlendSetupReport report;
  Eigen::MatrixX3i faces;
  // Internal frame: x_internal = (x - center) * scale; the reference is centred with unit area.
  Eigen::RowVector3d center = Eigen::RowVector3d::Zero();
  double scale = 1.0;
  BlendDictionary dictionary;  // examples in the internal frame, rigidly aligned to the reference
  detail::DictionaryProduct product;  // D T, the vertices of transformations, without holding D
  std::vector<int> clusters;   // per vertex
  int cluster_count = 0;
  Eigen::MatrixXd projected;   // G: N by 3 * clusters * K, block (k * clusters + c) = sum c_e (D_i - D_j)^T e_k^T
  Eigen::VectorXd example_energy;  // N_k = sum_e c_e |x^k_i - x^k_j|^2
  Eigen::MatrixXd base_initial;    // alpha_s Lambda + eps I
  Eigen::MatrixXd base_global;     // D^T L D + alpha_s Lambda + eps I
  Eigen::LLT<Eigen::MatrixXd> unconstrained;  // of base_global, for interpolation

  std::vector<LinearConstraint> constraints;
  Eigen::MatrixXd rows;            // #constraints by N: c_r^T D
  Eigen::VectorXd row_weights;     // alpha_c w_r
  Eigen::MatrixXd initial_matrix;  // base_initial + rows^T W rows
  Eigen::MatrixXd global_matrix;   // base_global + rows^T W rows
  Eigen::LLT<Eigen::MatrixXd> initial;
  Eigen::LLT<Eigen::MatrixXd> global;

  // The skeleton dictionary deformations change to, and the change (both null without one).
  std::unique_ptr<SkinningDecomposition> skinning;
  std::unique_ptr<BlendedDeformer> richer;
  std::unique_ptr<DictionaryChange> change;

  /// x = A^-1 b for the factor of A, the three columns of the maps in one pass over the factor each
  /// way (detail::cholesky_solve).
  static Eigen::MatrixX3d solve(const Eigen::LLT<Eigen::MatrixXd>& factor, const Eigen::Ref<const Eigen::MatrixX3d>& b);

  int atom_count() const { return static_cast<int>(product.cols()); }
  int example_count() const { return dictionary.example_count(); }
  int block_count() const { return cluster_count * example_count(); }

  /// The row c_r^T D of one constraint; throws ArgumentError for a bad constraint.
  Eigen::RowVectorXd constraint_row(const LinearConstraint& constraint) const;
  /// Targets in the internal frame.
  Eigen::MatrixX3d internal_targets(const Eigen::Ref<const Eigen::MatrixX3d>& targets) const;
  /// Rank-one change of both matrices and factors by sigma * row^T row; refactorizes when a downdate fails.
  void rank_update(const Eigen::RowVectorXd& row, double sigma);

  /// Local step: for every example k and cluster c the rotation closest to S_kc = T^T G_kc;
  /// dots(k) = sum_c <R_kc, S_kc>, which gives the closed-form scale.
  void local_step(const Eigen::Ref<const Eigen::MatrixX3d>& transformations, std::vector<Eigen::Matrix3d>& rotations,
                  Eigen::VectorXd& dots) const;
  /// side += sum over blocks j in [first, last) of G_j m_j (G_j: the three columns of block j, m_j:
  /// the 3 by 3 matrix at rows 3j of `stacked`), streaming the columns once, rows split over threads.
  void accumulate_blocks(int first, int last, const Eigen::Ref<const Eigen::MatrixX3d>& stacked,
                         Eigen::MatrixX3d& side) const;
  /// N by 3 ARAP part of the global step's right side: sum_k coefficients(k) sum_c G_kc R_kc^T
  /// (examples with coefficient 0 cost nothing).
  Eigen::MatrixX3d arap_right_side(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& coefficients) const;
  /// The closed-form scale, sum <R, S> / sum c_e |e|^2 over the examples concerned (1 when
  /// options.estimate_scale is off): the minimizer of the energy for fixed rotations and maps.
  double closed_form_scale(double dot, double energy) const;
  /// The initial transformations from the constraint part of the right side (N by 3), without
  /// rotations: one solve with the initial factors, or elastic-net coordinate descent when
  /// options.sparsity > 0. `energy` receives the initial energy less the constant sum w |p|^2.
  Eigen::MatrixX3d initial_solve(const Eigen::Ref<const Eigen::MatrixX3d>& right_side, double& energy) const;
};

}  // namespace posekit
