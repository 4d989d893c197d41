// The correction report as JSON: the schema of `posekit correct --report` (docs/correct.md).
#pragma once

#include <posekit/correct.hpp>

#include <nlohmann/json.hpp>

namespace posekit::cli {

/// The report with its three sections, `field`, `stages` (one entry per ladder stage, in order)
/// and `result`, plus the device, the mesh's size and the total wall time.
nlohmann::json correction_report_json(const CorrectionReport& report);

}  // namespace posekit::cli
