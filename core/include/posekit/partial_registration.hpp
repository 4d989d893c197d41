// Non-rigid ICP with blended transformations, and shape completion / partial registration of a scan:
// the full mesh of the examples is deformed, inside the space the examples span, until it fits the
// scan; the parts the scan lacks are completed by the model.
#pragma once

#include <posekit/blended_deformation.hpp>
#include <posekit/mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// Settings of the scan fit.
struct ScanFitOptions {
  /// Rounds of non-rigid ICP (match, then deform).
  int iterations = 10;
  /// Scan points used as constraints in each round, spread evenly over the scan's vertex order.
  int max_scan_points = 2000;
  /// Weight of each matched scan point relative to a feature point's weight of 1.
  double scan_weight = 0.05;
  /// A match counts only when the scan's normal and the mesh's normal there differ by less than this.
  double max_normal_angle_degrees = 60.0;
  /// Matches farther than this many times the median match distance are dropped.
  double rejection_factor = 3.0;
};

/// One round of non-rigid ICP.
struct ScanFitIteration {
  int matches = 0;               ///< scan points used as constraints
  double median_distance = 0.0;  ///< of the accepted matches, before the round's deformation
  double energy = 0.0;           ///< deformation energy after the round
  double seconds = 0.0;
};

/// The fitted full mesh and the correspondence of every scan vertex.
struct ScanRegistration {
  BlendResult initial;               ///< the deformation from the feature points alone
  BlendResult deformation;           ///< the final one; deformation.vertices is the completed mesh
  Eigen::VectorXi correspondence;    ///< per scan vertex: the nearest vertex of the fitted mesh
  Eigen::VectorXd distances;         ///< per scan vertex: its distance to that vertex
  std::vector<ScanFitIteration> iterations;
  double seconds = 0.0;
};

/// Non-rigid ICP from `start`: each round matches scan points to their closest points on the
/// current mesh (nearest vertex, then the closest point on its faces, with the normal test and the
/// distance rejection), adds each match as a weighted-average (barycentric) constraint to the fixed
/// `features` (vertex constraints of weight 1 at `feature_positions`), and deforms again from the
/// previous result. `scan` is any triangle mesh (#S by 3 vertices, faces for normals). Leaves
/// `deformer` with the last round's constraints. Throws ArgumentError on bad sizes or an empty scan.
ScanRegistration fit_to_scan(BlendedDeformer& deformer, const Mesh& scan, const std::vector<int>& features,
                             const Eigen::MatrixX3d& feature_positions, const BlendResult& start,
                             const ScanFitOptions& options = {});

/// Partial registration: deforms from the feature points (mesh vertices `features` known to lie at
/// the #features by 3 `feature_positions` on the scan), then runs fit_to_scan.
ScanRegistration register_partial_scan(BlendedDeformer& deformer, const Mesh& scan, const std::vector<int>& features,
                                       const Eigen::MatrixX3d& feature_positions, const ScanFitOptions& options = {});

}  // namespace posekit
