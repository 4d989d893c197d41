// Relief of stretch. A correction frees intersections by moving parts, and where it moves a vertex
// much farther than its neighbour the faces between them stretch (the field drags a part along, a
// blend into the target is narrower than the displacement it fades out). Such a region is given
// the target's own shape, displaced as its surroundings are, or is relaxed as-rigidly-as-possible
// towards that shape or the reference's; kept only where that adds no intersection and stretches
// fewer faces. Where a torn band around a limb cannot be relieved alone, the limb's tip beyond it,
// which the target held back, goes with the region.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"
#include "correct/region_sweep.hpp"

namespace posekit::detail {

/// Relieves the stretched faces of `candidate` (StretchMeasure of the context) region by region,
/// keeping a change only when the pose then has no more new faces and fewer stretched faces.
SweepOutcome relieve_stretch(Candidate& candidate, const CorrectionContext& context);

}  // namespace posekit::detail
