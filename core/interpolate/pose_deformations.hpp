// How every face deforms from pose 0 to each other pose: the rotation (as a rotation vector whose
// branch agrees across neighbouring faces) and the symmetric stretch of its deformation gradient.
// Blending these gives the gradient-space (Poisson) interpolation used to start edge-space fits.
#pragma once

#include <posekit/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::interpolation {

struct PoseDeformations {
  /// [k - 1][f]: rotation vector of face f from pose 0 to pose k, for k = 1 .. K-1.
  std::vector<std::vector<Eigen::Vector3d>> logs;
  /// [k - 1][f]: symmetric stretch of face f from pose 0 to pose k.
  std::vector<std::vector<Eigen::Matrix3d>> stretches;
};

/// The deformations of every face of `poses` (at least one pose).
PoseDeformations pose_deformations(const PoseSet& poses);

}  // namespace posekit::interpolation
