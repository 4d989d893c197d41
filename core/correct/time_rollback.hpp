// A repair for intersections that neither integration nor the target can remove: a region where
// the candidate still has new intersecting faces is moved back along its own path lines, relative
// to the surface around it, to the latest time at which it was clean.
//
// The region is a part that went too far: pressed into another part (the field stops it at the
// obstacle, but the mesh is compressed there below its edge length), or an intersection the
// reference already had that grew onto neighbouring faces on the way to the target. Along the
// path lines the region was clean at time 0 (the reference) and became entangled at some time;
// taking its shape at an earlier time, placed rigidly onto where its surroundings end up, keeps the
// rest of the correction and gives the part a little less of its motion.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"
#include "correct/region_sweep.hpp"

#include <functional>
#include <vector>

namespace posekit::detail {

/// Positions of `vertices` along their path lines at times k / segments of the whole motion,
/// k = 0 .. segments: element k is #vertices by 3, in the order given (PathLines::sample).
using PathSampler = std::function<std::vector<Eigen::MatrixX3d>(const std::vector<int>& vertices, int segments)>;

struct RollbackOptions {
  int segments = 10;     ///< times tried: 1 - 1/segments down to 0
  int blend_rings = 3;   ///< rings over which a moved region blends into the surface around it
  int anchor_rings = 2;  ///< rings beyond the blend that place the region's earlier shape
};

struct RollbackOutcome {
  SweepOutcome sweep;
  double earliest_time = 1;  ///< the earliest time a region was moved back to (1: none moved)
};

/// Moves regions of `candidate` around its new faces back along `paths`, each to the latest of the
/// tried times at which it no longer intersects, keeping a move only when it lowers the number of
/// new faces. Regions grow by one, then three, then six rings around the faces; a region whose
/// move would reach more than a tenth of the vertices is left alone. The candidate may differ from
/// the ends of the path lines (where the target was blended or copied in): the move along the path
/// lines is added to it.
RollbackOutcome roll_back_regions(Candidate& candidate, const CorrectionContext& context, const PathSampler& paths,
                                  const RollbackOptions& options = {});

}  // namespace posekit::detail
