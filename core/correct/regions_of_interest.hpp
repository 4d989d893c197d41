// Where the field correction works. Only near what intersects on the way from the reference to the
// target can the result differ from the target; everywhere else reproduction gives the target back
// anyway. So each field is fitted to a region of interest: the vertices the classification left
// unconstrained, with a collar of constrained vertices around them that pins the field where it
// meets the target. Regions that do not touch and do not pass through each other are independent.
#pragma once

#include "correct/vertex_classification.hpp"

#include <posekit/self_intersection_tracker.hpp>
#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::detail {

/// The unconstrained vertices of `classification` grown by `collar_rings` rings, as connected sets,
/// joined where a face of one intersects a face of another in some tested pose (`tested_pairs`).
/// Each region's vertices ascend; regions are largest first.
std::vector<std::vector<int>> regions_of_interest(const VertexClassification& classification,
                                                  const std::vector<FacePairs>& tested_pairs,
                                                  const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                                  const AdjacencyLists& neighbours,
                                                  int collar_rings);

/// One region holding every vertex, for the whole-mesh method.
std::vector<std::vector<int>> whole_mesh_region(int vertex_count);

}  // namespace posekit::detail
