// The scripts and style sheet every report page inlines, embedded at build time.
#pragma once

#include <string>

namespace posekit::report {

struct ReportAssets {
  std::string three;           ///< three.js (Debian's libjs-three, three.min.js)
  std::string orbit_controls;  ///< its OrbitControls
  std::string viewer;          ///< viewer/viewer.js: builds the page from the report's data
  std::string style;           ///< viewer/viewer.css
};

/// The embedded assets, joined once.
const ReportAssets& report_assets();

}  // namespace posekit::report
