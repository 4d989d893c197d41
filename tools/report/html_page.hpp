// The self-contained HTML page of a report: three.js, the viewer and the report's data inlined, so
// that the one file opens offline in any current browser.
#pragma once

#include "report_document.hpp"

#include <filesystem>
#include <string>

namespace posekit::report {

/// The page of `document`.
std::string html_page(const ReportDocument& document);

/// Writes the page of `document` to `file` whole or not at all (temporary file, then rename).
void write_html_report(const std::filesystem::path& file, const ReportDocument& document);

/// Throws ArgumentError naming `flag` and `file` when `file` cannot be written where it is named: its
/// folder is missing or is not a folder. Checked before a job's work, so that a report that could
/// not be written does not cost a whole computation.
void check_report_destination(const std::filesystem::path& file, const std::string& flag);

}  // namespace posekit::report
