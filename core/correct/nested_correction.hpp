// A correction run inside another: a region of the pose on its own, or a leg through the halfway
// pose. It is the whole pipeline (normalization, ladder, report) in a narrower scope, whose stages
// say themselves whether they run there.
#pragma once

#include "correct/correction_context.hpp"

#include <posekit/correct.hpp>

#include <memory>

namespace posekit::detail {

/// Corrects `target` against `reference` (#V by 3 each, in any frame) of the #F by 3 `faces` as
/// correct_pose() does, with the stages of `scope` only. The user's excluded vertices name vertices
/// of the whole pose and count only in CorrectionScope::whole_pose. `allowed` (sorted), when given,
/// replaces the reference's intersecting faces as those that may intersect: a leg that starts from
/// a corrected pose still owes the whole pose's reference what that pose left. `same_pair`, when it
/// holds an analysis, is that of a run of these same two poses (the wider collar's run, a first leg
/// again): what it holds is not computed again, and what this run computes is added to it.
Eigen::MatrixX3d correct_in_scope(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& target,
                                  const Eigen::Ref<const Eigen::MatrixX3i>& faces, Device& device,
                                  const CorrectionOptions& options,
                                  CorrectionScope scope, CorrectionReport* report = nullptr,
                                  const CorrectionProgress& progress = {}, const std::vector<int>* allowed = nullptr,
                                  LentAnalysis same_pair = {});

}  // namespace posekit::detail
