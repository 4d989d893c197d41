// The fallback for what integration cannot deliver: where the candidate still has intersections the
// reference does not have, the region around them is taken from the target, as the method's
// authors do for global intersections (a part of the key frames passing through another part on
// the way to a target where the two do not touch). Such a part is dragged along by the obstacle,
// so the region follows the vertices that strayed far from the target; smaller residues (an
// intersection the reference already had sliding onto a neighbouring face, a fold where the flow
// compresses the surface below the edge length) need only a few rings.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"
#include "correct/region_sweep.hpp"

#include <vector>

namespace posekit::detail {

struct FallbackOutcome {
  SweepOutcome sweep;
  int global_regions = 0;    ///< regions where the tested poses pass a part through another
  int smoothed_regions = 0;  ///< small regions smoothed instead, where the target's shape did not help
};

/// Gives regions of `candidate` the shape of the context's target until no new face is left or no
/// replacement helps. A region grows from the vertices of the new faces by one and three rings;
/// where it touches `in_transit` vertices (those only the in-between poses made unconstrained: a
/// global intersection) also through the vertices farther than `deviation_threshold` from the
/// target. The region takes the target's positions plus the harmonic interpolation of the offsets
/// candidate - target around it, and is kept only when that lowers the number of new faces. Where
/// no such region helps, the new faces' vertices (and then one more ring) are tried as a harmonic
/// membrane over their surroundings, which undoes folds inside corrected regions where the target
/// cannot help.
FallbackOutcome restore_target_regions(Candidate& candidate, const CorrectionContext& context,
                                       const std::vector<char>& in_transit, double deviation_threshold);

}  // namespace posekit::detail
