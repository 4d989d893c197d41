// The edge-space baseline: the whole mesh interpolated in edge lengths and dihedral angles and
// reconstructed by Gauss-Newton from a gradient-space start, then placed by the global pose parameters.
#pragma once

#include "interpolate/edge_space_reconstruction.hpp"
#include "interpolate/global_pose.hpp"

#include <posekit/edge_space.hpp>
#include <posekit/interpolate.hpp>

#include <memory>
#include <vector>

namespace posekit::interpolation {

class EdgeInterpolation {
 public:
  /// `poses` and `coordinates` (its edge-space coordinates on `edges`) must outlive this object.
  EdgeInterpolation(const PoseSet& poses, const EdgeMap& edges, const AdjacencyLists& incident_faces,
                    const EdgeSpaceCoordinates& coordinates, const InterpolationOptions& options,
                    PrecomputationTimes& times);

  /// The #V by 3 pose for normalized `weights`.
  Eigen::MatrixX3d interpolate(const Eigen::VectorXd& weights, InterpolationStepReport& report);

 private:
  const EdgeSpaceCoordinates& coordinates_;
  InterpolationOptions options_;
  int vertex_count_;
  const PoseSet& poses_;
  std::vector<std::vector<int>> pieces_;  // vertices of every edge-connected piece of the mesh
  std::unique_ptr<EdgeSpaceReconstruction> reconstruction_;
  std::unique_ptr<GlobalPose> global_pose_;
};

}  // namespace posekit::interpolation
