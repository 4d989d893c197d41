// A repair for folds. Where the stages before leave a region folded through itself (the flow
// compressed it below its edge length, a blend or a local correction creased it), the region is
// given back the reference's local shape, as rigidly as possible, with its surroundings held where
// they are. The target cannot help there: the region has strayed from it, or the target is itself
// entangled.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"
#include "correct/region_sweep.hpp"

#include <limits>

namespace posekit::detail {

/// Bounds of a relaxation.
struct RelaxationLimits {
  int widest_margin = 16;  ///< rings grown around a fold at most (of 1, 2, 3, 4, 6, 8, 12, 16)
  /// A relaxation that moves a vertex farther than this is not kept.
  double largest_move = std::numeric_limits<double>::infinity();
};

/// Relaxes regions of `candidate` around its new faces towards the local shape of the context's
/// reference, as-rigid-as-possible with the ring around each region held in place. A region grows
/// from the faces' vertices by 1, 2, 3, 4, 6, 8, 12 and 16 rings, up to a quarter of the vertices,
/// and is kept only when the whole pose then has fewer new faces; up to three rounds while they help.
SweepOutcome relax_folded_regions(Candidate& candidate, const CorrectionContext& context,
                                  const RelaxationLimits& limits = {});

}  // namespace posekit::detail
