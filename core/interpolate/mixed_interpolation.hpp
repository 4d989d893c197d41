// MixIT: interpolation in the mixed shape space of one pose set and one segmentation.
//
// Precomputation: joints and rigid pieces from the segmentation; every rigid piece registered across
// all poses; the factorizations that do not depend on the weights. Per weight vector: rigid pieces by
// linear interpolation of their registered copies, joints by a gradient-space start in their own frame
// (optionally refined in edge space), simultaneous registration of all components on their overlaps,
// stitching of the joints between the rigid pieces by least squares on edge vectors, an edge-space
// Gauss-Newton refinement of joints and rigid motions together, local/global passes over the whole
// mesh towards the interpolated lengths and angles, and the global placement.
#pragma once

#include "interpolate/articulated_refinement.hpp"
#include "interpolate/component_alignment.hpp"
#include "interpolate/edge_space_reconstruction.hpp"
#include "interpolate/edge_stitching.hpp"
#include "interpolate/global_pose.hpp"
#include "interpolate/joint_layout.hpp"
#include "interpolate/local_global_projection.hpp"

#include <posekit/edge_space.hpp>
#include <posekit/interpolate.hpp>

#include <memory>
#include <vector>

namespace posekit::interpolation {

class MixedInterpolation {
 public:
  /// Builds joints and rigid pieces from the #F `face_parts`. `poses` and `coordinates` (its edge-space
  /// coordinates on `edges`) must outlive this object. Adds its stage times to `times`.
  MixedInterpolation(const PoseSet& poses, const EdgeMap& edges, const AdjacencyLists& incident_faces,
                     const AdjacencyLists& neighbours, const EdgeSpaceCoordinates& coordinates,
                     const Eigen::VectorXi& face_parts, const InterpolationOptions& options, PrecomputationTimes& times);

  /// The #V by 3 pose for normalized `weights`.
  Eigen::MatrixX3d interpolate(const Eigen::VectorXd& weights, InterpolationStepReport& report);

  const InterpolationLayout& layout() const { return layout_summary_; }

 private:
  const PoseSet& poses_;
  const EdgeSpaceCoordinates& coordinates_;
  InterpolationOptions options_;
  JointLayout layout_;
  InterpolationLayout layout_summary_;
  std::vector<std::vector<Eigen::MatrixX3d>> aligned_pieces_;  // per rigid piece, per pose
  std::vector<std::unique_ptr<EdgeSpaceReconstruction>> joints_;
  std::vector<std::vector<int>> component_vertices_;  // rigid pieces, then joints
  std::unique_ptr<ComponentAlignment> alignment_;
  std::unique_ptr<EdgeStitching> stitching_;
  std::unique_ptr<ArticulatedRefinement> refinement_;
  std::unique_ptr<LocalGlobalProjection> projection_;
  std::unique_ptr<GlobalPose> global_pose_;
};

}  // namespace posekit::interpolation
