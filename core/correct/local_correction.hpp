// A second, local correction for what the stages before leave: where a region had to take the
// target's shape (the field dragged it, or the tested poses pass it through another part) and the
// target is itself entangled there, the region alone is corrected again, from the reference's
// region to the region as it now is. On its own the region has no part to pass through, so its own
// key frames and field can do what the whole pose's could not.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"
#include "correct/region_sweep.hpp"

namespace posekit::detail {

/// Corrects regions of `candidate` around its new faces, each as a mesh of its own from the
/// context's reference to the candidate (a nested correction in CorrectionScope::region), blended
/// into the unchanged surroundings over `blend_rings` rings, and keeps a region's correction only
/// when the whole pose then has fewer new faces. A region is grown by 4, 8, then 16 rings around the
/// faces, joined with the regions its faces intersect, and left alone beyond half of the vertices;
/// the passes repeat, up to three times, while they help.
SweepOutcome correct_regions_locally(Candidate& candidate, const CorrectionContext& context);

/// Whether the local correction also corrects the target's own regions, after the candidate's pass
/// took the candidate from `faces_before` new faces to `faces_left`: only where faces are left and
/// that pass freed under three quarters of them.
bool target_pass_wanted(int faces_before, int faces_left);

}  // namespace posekit::detail
