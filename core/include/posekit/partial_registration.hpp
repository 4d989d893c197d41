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
  /// Rounds of non-rigid ICP (match, then deform; >= 0).
  int iterations = 10;
  /// Local/global iterations of each round's deformation, which starts from the previous round's:
  /// average-ARAP ones (which pull towards the mean of the examples) and minimal-ARAP ones (>= 0).
  int round_average_iterations = 0;
  int round_minimal_iterations = 4;
  /// Scan points used as constraints in each round, spread evenly over the scan's vertex order (>= 1).
  int max_scan_points = 2000;
  /// Weight of each matched scan point relative to a feature constraint's weight of 1 (> 0).
  double scan_weight = 0.05;
  /// A match counts only when the scan's normal and the mesh's normal there differ by less than this
  /// angle, in degrees (in (0, 180]).
  double max_normal_angle_degrees = 60.0;
  /// Matches farther than this many times the median match distance are dropped (> 0).
  double rejection_factor = 3.0;
  /// Geodesic discs around each feature point whose weighted centroids are constrained too, with
  /// radii radius * i / rings for i = 1..rings; 0 keeps only the feature points themselves (>= 0).
  int feature_rings = 10;
  /// Largest disc radius, as a fraction of the square root of the reference's area (> 0).
  double feature_radius = 0.15;
  /// Lengths on the scan per unit length of the examples (1: the scan is in the examples' units; the
  /// deformation finds its own scale, this only sizes the discs on the scan). > 0.
  double scan_scale = 1.0;
};

/// The constraints that feature points give: each point itself and, where the scan holds the whole
/// disc, the centroids of geodesic discs around it.
struct FeatureConstraints {
  std::vector<LinearConstraint> constraints;
  Eigen::MatrixX3d targets;  ///< one row per constraint, on the scan
  int discs = 0;             ///< disc centroids among the constraints
};

/// Feature constraints for `deformer` from mesh vertices `features` known to lie at the #features by 3
/// `feature_positions` on `scan`. A disc of radius r is measured (by shortest paths along edges) on
/// the reference around the feature vertex and on the scan (r times options.scan_scale) around its
/// vertex nearest the feature position; a disc is used only when no scan boundary vertex lies within
/// it. A disc's centroid weighs each vertex by its lumped mass times (1 - (d/r)^2)^2, smooth down to
/// zero at the rim. Throws ArgumentError on bad sizes, an index out of range, a bad option or an
/// empty scan.
FeatureConstraints feature_constraints(const BlendedDeformer& deformer, const Mesh& scan, const std::vector<int>& features,
                                       const Eigen::Ref<const Eigen::MatrixX3d>& feature_positions,
                                       const ScanFitOptions& options = {});

/// One round of non-rigid ICP.
struct ScanFitIteration {
  int matches = 0;               ///< scan points used as constraints
  double median_distance = 0.0;  ///< of the accepted matches, before the round's deformation
  double energy = 0.0;           ///< deformation energy after the round
  double seconds = 0.0;
};

/// The fitted full mesh and the correspondence of every scan vertex.
struct ScanRegistration {
  BlendResult initial;               ///< the deformation from the feature constraints alone
  BlendResult deformation;           ///< the final one; deformation.vertices is the completed mesh
  Eigen::VectorXi correspondence;    ///< per scan vertex: the nearest vertex of the fitted mesh
  Eigen::VectorXd distances;         ///< per scan vertex: its distance to that vertex
  std::vector<ScanFitIteration> iterations;
  int feature_discs = 0;             ///< disc centroids used with the feature points
  double seconds = 0.0;
};

/// Non-rigid ICP from `start`: each round matches scan points to their closest points on the
/// current mesh (nearest vertex, then the closest point on its faces, with the normal test and the
/// distance rejection), adds each match as a weighted-average (barycentric) constraint to the `fixed`
/// ones (at `fixed_targets`, one row each), and deforms again from the previous result. `scan` is any
/// triangle mesh (#S by 3 vertices; faces give the normals). Leaves `deformer` with the last round's
/// constraints. Throws ArgumentError on bad sizes or an empty scan.
ScanRegistration fit_to_scan(BlendedDeformer& deformer, const Mesh& scan, const std::vector<LinearConstraint>& fixed,
                             const Eigen::Ref<const Eigen::MatrixX3d>& fixed_targets, const BlendResult& start,
                             const ScanFitOptions& options = {});

/// Partial registration: the feature constraints (feature_constraints()), a deformation from them
/// alone, then fit_to_scan with them as the fixed constraints.
ScanRegistration register_partial_scan(BlendedDeformer& deformer, const Mesh& scan, const std::vector<int>& features,
                                       const Eigen::Ref<const Eigen::MatrixX3d>& feature_positions,
                                       const ScanFitOptions& options = {});

}  // namespace posekit
