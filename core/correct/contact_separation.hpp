// Separation of the target's own contacts. Where parts of the target press into each other over
// much of the pose (a cat curled up asleep, its head sunk into its paws), the field's correction
// moves whole parts off the target. Starting from the target instead, each part is pushed back
// into itself where it lies inside another (half the depth each, as two soft bodies flatten
// against each other), the surface around follows as-rigidly-as-possible, and what folds is
// relaxed towards the reference's local shape; the rest of the pose stays the target exactly.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace posekit::detail {

struct SeparationResult {
  Eigen::MatrixX3d pose;    ///< the pose with the fewest new intersecting faces reached
  int new_faces_before = 0; ///< new intersecting faces of the target
  int new_faces_after = 0;  ///< and of `pose`
  int iterations = 0;       ///< push and relaxation rounds run
};

/// Generalized winding number of the closed surface (`vertices`, `faces`) at each of `points`
/// (#P by 3): about 1 inside, 0 outside, 1/2 on the surface, 3/2 on it and inside another part.
Eigen::VectorXd winding_numbers(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                const Eigen::MatrixX3d& points);

/// Separates the contacts of `target` (#V by 3) that intersect and are not in
/// `reference_intersecting` (sorted), with `reference` (#V by 3, same connectivity) giving the
/// shape a fold relaxes to. Up to twenty rounds; vertices away from the contacts keep the target's
/// position exactly.
SeparationResult separate_contacts(const Eigen::MatrixX3d& target, const Eigen::MatrixX3d& reference,
                                   const Eigen::MatrixX3i& faces, const std::vector<int>& reference_intersecting);

}  // namespace posekit::detail
