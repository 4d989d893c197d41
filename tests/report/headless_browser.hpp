// Opens a report in headless Chromium (software WebGL): its final DOM, console lines and screenshots.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace posekit::testing {

/// Why the browser tests cannot run here (no Chromium found at configure time); empty when they can.
std::string browser_unavailable();

/// What a page left behind once loaded and rendered.
struct PageState {
  std::string status;                         ///< the body's data-status ("ready" once drawn)
  int errors = -1;                            ///< the body's data-errors (errors the page caught)
  std::vector<std::string> console_messages;  ///< the page's console lines, browser notes left out
  std::string dom;
};

/// Loads `page` (with `fragment`, e.g. "#frame=3", appended to its URL) and returns its state.
PageState load_page(const std::filesystem::path& page, const std::string& fragment = "");

/// An RGB screenshot, row by row from the top.
struct Screenshot {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgb;
  /// Pixels in the top `fraction_of_height` of the picture for which `test(r, g, b)` holds.
  int count(const std::function<bool(int, int, int)>& test, double fraction_of_height = 1.0) const;
};

/// A 1280 by 800 screenshot of `page` (with `fragment`) once drawn.
Screenshot screenshot(const std::filesystem::path& page, const std::string& fragment = "");

/// Saturated red, as reports paint intersecting faces.
bool is_red(int r, int g, int b);

/// Pixels that differ by more than 40 in some channel between two screenshots of one size.
int differing_pixels(const Screenshot& a, const Screenshot& b);

}  // namespace posekit::testing
