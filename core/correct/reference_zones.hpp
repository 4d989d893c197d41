// Repair of the reference's own intersections where they slid. Where the reference already has
// parts passing through each other (a crease folded through itself, two limbs crossing), the
// target often has the crossing a face or two further along, and the correction keeps those faces
// at the target: they are new. The zone of the reference's intersection, with the new faces that
// touch it, takes the reference's own shape there, placed rigidly onto where its surroundings are
// and blended in: the crossing is the reference's again.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"
#include "correct/region_sweep.hpp"

namespace posekit::detail {

/// The new faces of `candidate` that intersect one of the reference's intersecting faces, sorted.
std::vector<int> faces_on_reference_zones(const Candidate& candidate, const std::vector<int>& reference_intersecting);

/// Gives each zone of the reference's intersections that new faces of `candidate` touch the
/// reference's shape, rigidly placed onto the ring around it and blended over a few rings, where
/// that leaves fewer new faces.
SweepOutcome restore_reference_zones(Candidate& candidate, const CorrectionContext& context);

}  // namespace posekit::detail
