// The sequence report as JSON: the schema of `posekit correct-sequence --report`
// (docs/correct-sequence.md).
#pragma once

#include <posekit/correct_sequence.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace posekit::cli {

/// `sequence` (counts, coherence, times) and `frames` (one entry per frame, named by `names`, with
/// the correction report of each frame corrected itself in this run).
nlohmann::json sequence_report_json(const SequenceReport& report, const std::vector<FrameCorrection>& frames,
                                    const std::vector<std::string>& names, const std::string& device);

}  // namespace posekit::cli
