// Poses in edge space: the length and the dihedral angle of every edge, the rotation-invariant
// coordinates in which joints are interpolated (and the edge-space baseline works).
#pragma once

#include <posekit/geometry.hpp>
#include <posekit/mesh.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit {


/// Edge lengths and dihedral angles of every pose of a pose set.
struct EdgeSpaceCoordinates {
  /// #E by K edge lengths, one column per pose.
  Eigen::MatrixXd lengths;
  /// #E by K signed dihedral angles in radians (see dihedral_angles), each pose's angle moved by a
  /// multiple of 2 pi to lie within pi of pose 0's, so that linear combinations take the short way
  /// round; NaN on edges that are not hinges.
  Eigen::MatrixXd angles;
  /// #E flags: 1 for a hinge, an edge with exactly two faces, neither degenerate in any pose
  /// (twice its area below 1e-10 times its longest edge squared), so its angle means something.
  std::vector<char> hinge;
  /// #F flags: 1 for a face that is degenerate in at least one pose.
  std::vector<char> degenerate_face;

  int edge_count() const { return static_cast<int>(lengths.rows()); }
  int pose_count() const { return static_cast<int>(lengths.cols()); }
  /// Linear combination of the poses' lengths with the K `weights`: #E values.
  Eigen::VectorXd combined_lengths(const Eigen::VectorXd& weights) const { return lengths * weights; }
  /// The same, but never below a thousandth of the edge's shortest length in any pose: weights that
  /// extrapolate far may ask for lengths at or below zero, which no mesh has.
  Eigen::VectorXd combined_positive_lengths(const Eigen::VectorXd& weights) const {
    return (lengths * weights).cwiseMax(1e-3 * lengths.rowwise().minCoeff());
  }
  /// Linear combination of the poses' (unwrapped) angles with the K `weights`: #E values, NaN off hinges.
  Eigen::VectorXd combined_angles(const Eigen::VectorXd& weights) const { return angles * weights; }
};

/// Edge-space coordinates of every pose of `poses` on the edges of `edges` = edge_map(poses.faces()),
/// with `incident_faces` = edge_faces(edges). Throws ArgumentError when the pose set has no pose or
/// the maps do not belong to its faces.
EdgeSpaceCoordinates edge_space_coordinates(const PoseSet& poses, const EdgeMap& edges,
                                            const AdjacencyLists& incident_faces);

/// `angle` moved by a multiple of 2 pi into [-pi, pi].
double wrap_angle(double angle);

}  // namespace posekit
