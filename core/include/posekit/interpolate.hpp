// Interpolation of articulated poses in a mixed shape space (MixIT, Marras, Cashman and Hormann):
// rigid parts are registered across the poses and interpolated vertex by vertex, joints (strips of
// triangles around part boundaries) are interpolated in edge space (lengths and dihedral angles),
// and the pieces are aligned, stitched by least squares on edge vectors, refined together in edge
// space and placed by interpolated global pose parameters. Two baselines share the interface: linear
// vertex interpolation and whole-mesh edge-space interpolation (Gauss-Newton from a gradient-space start).
//
// Weights: one per pose, summing to 1 (an affine combination; negative weights extrapolate). For two
// poses, weight vector (1 - t, t) goes from pose 0 at t = 0 to pose 1 at t = 1.
#pragma once

#include <posekit/interpolation_error.hpp>
#include <posekit/mesh.hpp>
#include <posekit/rigid_segmentation.hpp>

#include <Eigen/Core>

#include <memory>
#include <string>

namespace posekit {

enum class InterpolationMethod {
  mixit,   ///< mixed shape space: rigid parts in vertex space, joints in edge space
  edge,    ///< the whole mesh in edge space
  vertex,  ///< linear interpolation of vertex positions
};

/// "mixit", "edge" or "vertex".
std::string to_string(InterpolationMethod method);
/// The method named by `name` ("mixit", "edge" or "vertex"); throws ArgumentError otherwise.
InterpolationMethod interpolation_method_from_string(const std::string& name);

/// Parameters of PoseInterpolator; the defaults are those the shared poses were measured with.
struct InterpolationOptions {
  InterpolationMethod method = InterpolationMethod::mixit;
  /// Triangle strips of a joint on each side of a part boundary (>= 1); rigid parts keep the last one,
  /// so parts and joints overlap by one strip.
  int joint_width = 3;
  /// #F part ids given by the user (any non-negative integers; a label whose faces fall apart gives one
  /// part per piece); empty: segment_rigid_parts() with `segmentation`.
  Eigen::VectorXi face_parts;
  SegmentationOptions segmentation;
  /// Gauss-Newton iterations in edge space: of each joint alone before the alignment (mixit), of all
  /// joints together with the rigid motions of the parts after the stitching (mixit), and of the whole
  /// mesh (edge), each after a gradient-space start (>= 0).
  int joint_iterations = 0;
  int refinement_iterations = 2;
  int edge_iterations = 20;
  /// Local/global passes over the whole mesh towards the interpolated edge lengths and dihedral angles
  /// at the end (mixit, >= 0), with hinges weighing this much against an edge's length (>= 0).
  int projection_passes = 5;
  double projection_hinge_weight = 0.5;
  /// Weight of squared dihedral-angle errors (radians) against squared relative edge-length errors in
  /// the edge-space fit (> 0).
  double bending_weight = 0.1;
  /// Rounds of simultaneous registration of the components after the spanning tree (>= 0).
  int alignment_sweeps = 10;
};

/// Size of the mixed shape space built for a pose set.
struct InterpolationLayout {
  int parts = 0;          ///< parts of the segmentation
  int rigid_pieces = 0;   ///< rigid parts after shrinking (a part may fall into several pieces or vanish)
  int joints = 0;
  int joint_faces = 0;
  int joint_edges = 0;
  int rigid_vertices = 0;  ///< vertices of rigid pieces, counted once per piece
  /// dim S_m = 2 * (joint edges) + 3 * (rigid vertices) + 6, and dim S_e = 2 * #E for comparison.
  long long mixed_dimension = 0;
  long long edge_dimension = 0;
};

/// Seconds spent preparing an interpolator.
struct PrecomputationTimes {
  double edge_space = 0, segmentation = 0, layout = 0, registration = 0, factorization = 0, total = 0;
};

/// Seconds spent on one weight vector, by stage: the linear blends (rigid parts, edge-space targets),
/// the joints' own reconstruction (for the edge method: the whole mesh), the alignment of the
/// components, the stitching, the joint refinement, the final local/global passes and the global
/// placement (stages a method does not have stay 0).
struct InterpolationTimes {
  double blend = 0, joints = 0, alignment = 0, stitching = 0, refinement = 0, projection = 0, placement = 0, total = 0;
};

struct InterpolationStepReport {
  InterpolationTimes seconds;
  /// Gauss-Newton iterations done: per joint summed plus those of the joint refinement (mixit), or of
  /// the whole mesh (edge).
  int gauss_newton_iterations = 0;
};

/// Prepares the interpolation of one pose set with one method, then interpolates any number of weight
/// vectors with that preparation (segmentation, registration and factorizations done once).
class PoseInterpolator {
 public:
  /// Takes at least two poses. Throws ArgumentError for fewer poses, `options` out of range, or
  /// face_parts of the wrong size.
  explicit PoseInterpolator(PoseSet poses, const InterpolationOptions& options = {});
  ~PoseInterpolator();
  PoseInterpolator(PoseInterpolator&&) noexcept;
  PoseInterpolator& operator=(PoseInterpolator&&) noexcept;

  /// The #V by 3 pose for the K `weights` (one per pose, finite, summing to 1 within 1e-4; they are
  /// rescaled to sum to 1 exactly). Throws ArgumentError otherwise. Not safe to call concurrently on
  /// one interpolator.
  Eigen::MatrixX3d interpolate(const Eigen::VectorXd& weights, InterpolationStepReport* report = nullptr);

  /// The error of `result` against the edge lengths and dihedral angles interpolated with `weights`.
  InterpolationError error(const Eigen::Ref<const Eigen::MatrixX3d>& result, const Eigen::VectorXd& weights) const;
  /// Per vertex, the largest relative edge-length error of its edges in `result` (see error()).
  Eigen::VectorXd vertex_edge_length_errors(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                            const Eigen::VectorXd& weights) const;

  const PoseSet& poses() const;
  const InterpolationOptions& options() const;
  /// #F part ids used by mixit (empty for the other methods).
  const Eigen::VectorXi& face_parts() const;
  /// Mixed shape space sizes (mixit; zeros but edge_dimension otherwise).
  const InterpolationLayout& layout() const;
  const PrecomputationTimes& precomputation_seconds() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The weights (1 - t, t) of two poses.
Eigen::VectorXd two_pose_weights(double t);

/// `weights` checked (K = `pose_count` finite entries summing to 1 within 1e-4) and rescaled to sum to
/// 1 exactly; throws ArgumentError naming the problem otherwise.
Eigen::VectorXd normalized_weights(const Eigen::VectorXd& weights, int pose_count);

/// Everything one call to interpolate_poses() measured.
struct InterpolationReport {
  InterpolationLayout layout;
  PrecomputationTimes precomputation;
  InterpolationStepReport step;
  InterpolationError error;
};

/// One-shot interpolation: PoseInterpolator(poses, options).interpolate(weights), with its error.
Eigen::MatrixX3d interpolate_poses(const PoseSet& poses, const Eigen::VectorXd& weights,
                                   const InterpolationOptions& options = {}, InterpolationReport* report = nullptr);

}  // namespace posekit
