#include "interpolate/pose_deformations.hpp"

#include <posekit/face_deformation.hpp>
#include <posekit/rigid_motion.hpp>

#include <tbb/parallel_for.h>

namespace posekit::interpolation {

PoseDeformations pose_deformations(const PoseSet& poses) {
  PoseDeformations result;
  const int face_count = static_cast<int>(poses.faces().rows());
  for (int k = 1; k < poses.pose_count(); ++k) {
    const std::vector<Eigen::Matrix3d> gradients = face_deformation_gradients(poses.pose(0), poses.pose(k), poses.faces());
    std::vector<Eigen::AngleAxisd> rotations(static_cast<size_t>(face_count));
    std::vector<Eigen::Matrix3d> stretches(static_cast<size_t>(face_count));
    tbb::parallel_for(0, face_count, [&](int f) {
      const PolarDecomposition polar = polar_decomposition(gradients[static_cast<size_t>(f)]);
      rotations[static_cast<size_t>(f)] = Eigen::AngleAxisd(polar.rotation);
      stretches[static_cast<size_t>(f)] = polar.stretch;
    });
    result.logs.push_back(consistent_rotation_logs(rotations, poses.faces()));
    result.stretches.push_back(std::move(stretches));
  }
  return result;
}

}  // namespace posekit::interpolation
