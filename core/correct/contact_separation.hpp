// Separation of the target's own contacts. Where parts of the target press into each other over
// much of the pose (an animal curled up, its head sunk into its paws), the field's
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
  int new_faces_before = 0;  ///< new faces of the start
};

/// Separates the contacts of `start` (the context's target, or a candidate) that intersect and are
/// not the reference's: each round relaxes folds towards the context's reference shape, pushes
/// every vertex lying inside another part back into its own, and lets the ring around follow
/// `start`'s own shape as-rigidly-as-possible. Up to twenty rounds, fewer when three in a row bring
/// nothing better; vertices away from the contacts keep `start`'s positions exactly.
SeparationOutcome separate_contacts(const CorrectionContext& context, Candidate start);

}  // namespace posekit::detail
