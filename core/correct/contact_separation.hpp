// Separation of the target's own contacts. Where parts of the target press into each other over
// much of the pose (an animal curled up asleep, its head sunk into its paws), the field's
// correction moves whole parts off the target. Starting from the target instead, each part is
// pushed back into itself where it lies inside another (half the depth each, as two soft bodies
// flatten against each other), the surface around follows as-rigidly-as-possible, and what folds is
// relaxed towards the reference's local shape; the rest of the pose stays the target exactly.
#pragma once

#include "correct/candidate.hpp"
#include "correct/correction_context.hpp"

namespace posekit::detail {

struct SeparationOutcome {
  Candidate best;            ///< the pose with the fewest new faces reached
  int rounds = 0;            ///< push and relaxation rounds run
  int new_faces_before = 0;  ///< new faces of the target
};

/// Separates the contacts of the context's target that intersect and are not the reference's, with
/// the context's reference giving the shape a fold relaxes to. Up to twenty rounds; vertices away
/// from the contacts keep the target's position exactly.
SeparationOutcome separate_contacts(const CorrectionContext& context);

}  // namespace posekit::detail
