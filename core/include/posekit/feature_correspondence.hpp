// Automatic correspondence of ambiguous feature points: when the positions of some features are
// known but not which mesh vertex each belongs to (the four feet of a horse), every permissible
// assignment is deformed and the one of least deformation energy is kept.
#pragma once

#include <posekit/blended_deformation.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace posekit {

/// Every assignment of `vertices` to their positions that permutes vertices only among features with
/// the same non-empty group label (features with label "" stay fixed). The first assignment is
/// `vertices` itself; their number is the product of the factorials of the group sizes. Throws
/// ArgumentError when the sizes differ or there would be more than `limit` assignments.
std::vector<std::vector<int>> permissible_assignments(const std::vector<int>& vertices,
                                                      const std::vector<std::string>& groups, size_t limit = 40320);

/// The outcome of choose_correspondence.
struct CorrespondenceChoice {
  int assignment = 0;            ///< index of the chosen assignment
  std::vector<int> vertices;     ///< the chosen vertex of each position
  std::vector<double> energies;  ///< final deformation energy of every assignment
  BlendResult result;            ///< the deformation of the chosen assignment
};

/// Deforms with each assignment (a list of vertex indices, one per row of the #features by 3
/// `positions`; all assignments of equal length) as vertex constraints of weight `weight` and keeps
/// the one whose final (minimal-ARAP) energy is lowest. Between assignments only the constraints that
/// change are replaced, by rank-one updates of the factorization. Leaves `deformer` constrained by
/// the chosen assignment. Throws ArgumentError for no assignment or mismatched sizes.
CorrespondenceChoice choose_correspondence(BlendedDeformer& deformer,
                                           const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                           const std::vector<std::vector<int>>& assignments, double weight = 1.0);

}  // namespace posekit
