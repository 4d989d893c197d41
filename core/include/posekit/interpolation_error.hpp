// How far an interpolated pose is from the linearly interpolated edge lengths and dihedral angles of
// its input poses: the error measures of Winkler et al. used to compare interpolation methods, and
// counts of collapsed faces and folded edges.
#pragma once

#include <posekit/edge_space.hpp>
#include <posekit/mesh.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>

namespace posekit {

/// The largest value and the 99.9th and 99th percentiles (nearest rank) of a set of errors.
struct ErrorPercentiles {
  double max = 0.0;
  double p999 = 0.0;
  double p99 = 0.0;
};

/// Errors of one interpolated pose against the targets l* = sum_k w_k l_k and theta* = sum_k w_k theta_k.
struct InterpolationError {
  ErrorPercentiles edge_length;       ///< |l - l*| / l* over all edges
  ErrorPercentiles dihedral_degrees;  ///< |theta - theta*| in degrees over all hinges
  /// Faces whose area is below a quarter of the smallest area the face has in any input pose.
  int collapsed_faces = 0;
  /// Hinges whose dihedral angle is more than 90 degrees from its target: a face turned over.
  int folded_edges = 0;
  /// Faces whose normal points against its normal in every input pose, carried over by the rotation
  /// that best moves each corner's one-ring from that pose onto the result: turned inside out.
  int flipped_faces = 0;
  /// Whether every coordinate of the pose is finite (the other fields are meaningless otherwise).
  bool finite = true;
};

/// Measures interpolated poses of one pose set; keeps the pose set's edge-space coordinates.
class InterpolationErrorMeter {
 public:
  /// Takes the edge-space coordinates of `poses` (at least one pose).
  explicit InterpolationErrorMeter(const PoseSet& poses);
  /// The same from precomputed pieces of `poses`: `edges` = edge_map(faces), `incident_faces` =
  /// edge_faces(edges), `neighbours` = vertex_neighbours(faces, #V) and the poses' `coordinates`.
  InterpolationErrorMeter(const PoseSet& poses, EdgeMap edges, AdjacencyLists incident_faces, AdjacencyLists neighbours,
                          EdgeSpaceCoordinates coordinates);

  /// Errors of the #V by 3 `result` against the targets for the K `weights` (one per pose).
  /// Throws ArgumentError on mismatched sizes.
  InterpolationError measure(const Eigen::Ref<const Eigen::MatrixX3d>& result, const Eigen::VectorXd& weights) const;

  /// Per vertex of `result`, the largest relative edge-length error |l - l*| / l* of its edges (0 for a
  /// vertex without edges of positive target length): where on the surface the error of measure() lies.
  Eigen::VectorXd vertex_edge_length_errors(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                            const Eigen::VectorXd& weights) const;

  const EdgeSpaceCoordinates& coordinates() const { return coordinates_; }

 private:
  /// Throws ArgumentError unless there is one weight per pose and the faces index `result`'s vertices.
  void check_arguments(const Eigen::Ref<const Eigen::MatrixX3d>& result, const Eigen::VectorXd& weights) const;
  /// |l - l*| / l* per edge, NaN where the target length is 0.
  Eigen::VectorXd edge_length_errors(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                     const Eigen::VectorXd& weights) const;
  int flipped_faces(const Eigen::Ref<const Eigen::MatrixX3d>& result) const;

  PoseSet poses_;
  Eigen::MatrixX3i faces_;
  EdgeMap edges_;
  AdjacencyLists incident_faces_;
  AdjacencyLists neighbours_;
  EdgeSpaceCoordinates coordinates_;
  Eigen::VectorXd reference_areas_;
};

/// One-shot: InterpolationErrorMeter(poses).measure(result, weights).
InterpolationError interpolation_error(const Eigen::Ref<const Eigen::MatrixX3d>& result, const PoseSet& poses,
                                       const Eigen::VectorXd& weights);

/// Smallest area of each face over all poses of `poses`: #F values.
Eigen::VectorXd smallest_face_areas(const PoseSet& poses);

}  // namespace posekit
