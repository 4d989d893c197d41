// The repair ladder: the stages of a correction in their order, as data, and the one loop that runs
// them on a candidate, keeping each stage's proposal only when it is better.
#pragma once

#include "correct/repair_stage.hpp"

#include <vector>

namespace posekit::detail {

/// The stages of correct_pose() in the order they run.
RepairLadder default_repair_ladder();

/// Runs every stage of `ladder` on `start` in order: a stage runs when the options enable it, the
/// context's scope includes it, it is wanted and no stage of its repair ran on the same candidate
/// before; its proposal replaces the candidate when better (better()). Appends one entry per stage
/// to `reports`, run or not, and returns the last candidate.
Candidate run_repair_ladder(const RepairLadder& ladder, Candidate start, CorrectionContext& context,
                            std::vector<StageReport>& reports);

/// Throws ArgumentError when `disabled` names a stage that is not optional or not in the ladder.
void check_disabled_stages(const std::vector<std::string>& disabled);

}  // namespace posekit::detail
