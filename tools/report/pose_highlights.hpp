// What every report marks the same way: intersecting faces (red where the reference has none, amber
// where it has its own), the distance a job moved each vertex, and the regions it moved.
#pragma once

#include "report_document.hpp"

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::report {

inline constexpr const char* kNewIntersectionColour = "#e00000";
inline constexpr const char* kReferenceIntersectionColour = "#e8a33d";
inline constexpr const char* kDiagonalUnit = "of the diagonal";

/// The face sets of a pose's `intersecting` faces against the reference's `reference_intersecting`
/// (both ascending): those the reference has too (amber), then the new ones (red). Empty sets are left out.
std::vector<FaceSet> intersection_sets(const std::vector<int>& intersecting, const std::vector<int>& reference_intersecting);

/// |to - from| per vertex, over `diagonal`.
Eigen::VectorXd moved_fraction(const Eigen::Ref<const Eigen::MatrixX3d>& from, const Eigen::Ref<const Eigen::MatrixX3d>& to,
                               double diagonal);

/// The connected sets of vertices with a positive `moved` (moved_fraction), largest first and at most
/// `limit` of them, as regions of `pose`: their bounding boxes' centres and half diagonals.
std::vector<Region> moved_regions(const Eigen::VectorXd& moved, const AdjacencyLists& neighbours,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& pose, int limit = 24);

}  // namespace posekit::report
