#include "headless_browser.hpp"

#include "command_runner.hpp"
#include "test_data.hpp"

#include <png.h>

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace posekit::testing {
namespace {

constexpr const char* kChromium = POSEKIT_CHROMIUM;

// Software WebGL (SwiftShader) so that no GPU is needed; each run gets its own profile so that runs in
// parallel do not share one; a time budget lets the page load, draw and settle before the dump.
std::vector<std::string> browser_arguments(const std::filesystem::path& profile) {
  return {"120",
          kChromium,
          "--headless",
          "--no-sandbox",
          "--disable-dev-shm-usage",
          "--use-angle=swiftshader",
          "--enable-unsafe-swiftshader",
          "--no-first-run",
          "--hide-scrollbars",
          "--user-data-dir=" + profile.string(),
          "--window-size=1280,800",
          "--virtual-time-budget=10000"};
}

std::string page_url(const std::filesystem::path& page, const std::string& fragment) {
  return "file://" + std::filesystem::absolute(page).string() + fragment;
}

std::string attribute(const std::string& dom, const std::string& name) {
  std::smatch match;
  if (std::regex_search(dom, match, std::regex("<body[^>]*\\s" + name + "=\"([^\"]*)\""))) return match[1];
  return {};
}

}  // namespace

std::string browser_unavailable() {
  if (std::string(kChromium).empty()) return "Chromium was not found when the tests were configured";
  return {};
}

PageState load_page(const std::filesystem::path& page, const std::string& fragment) {
  TemporaryDirectory profile;
  std::vector<std::string> arguments = browser_arguments(profile.path());
  arguments.insert(arguments.end(), {"--enable-logging=stderr", "--v=0", "--dump-dom", page_url(page, fragment)});
  const CommandResult run = run_program("timeout", arguments);
  if (run.exit_status != 0) throw std::runtime_error("chromium --dump-dom exited with " + std::to_string(run.exit_status) + ": " + run.err);
  PageState state;
  state.dom = run.out;
  state.status = attribute(run.out, "data-status");
  const std::string errors = attribute(run.out, "data-errors");
  state.errors = errors.empty() ? -1 : std::atoi(errors.c_str());
  for (const std::string& line : run.err_lines()) {
    if (line.find(":CONSOLE") == std::string::npos) continue;
    // The browser's own performance notes about reading pixels back are not the page's messages.
    if (line.find("GL Driver Message") != std::string::npos) continue;
    state.console_messages.push_back(line);
  }
  return state;
}

int Screenshot::count(const std::function<bool(int, int, int)>& test, double fraction_of_height) const {
  const int rows = static_cast<int>(fraction_of_height * height);
  int found = 0;
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < width; ++x) {
      const size_t at = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
      if (test(rgb[at], rgb[at + 1], rgb[at + 2])) ++found;
    }
  }
  return found;
}

Screenshot screenshot(const std::filesystem::path& page, const std::string& fragment) {
  TemporaryDirectory profile;
  const std::filesystem::path file = profile.path() / "screenshot.png";
  std::vector<std::string> arguments = browser_arguments(profile.path() / "profile");
  arguments.insert(arguments.end(), {"--screenshot=" + file.string(), page_url(page, fragment)});
  const CommandResult run = run_program("timeout", arguments);
  if (run.exit_status != 0) throw std::runtime_error("chromium --screenshot exited with " + std::to_string(run.exit_status) + ": " + run.err);

  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, file.string().c_str())) {
    throw std::runtime_error("cannot read the screenshot " + file.string() + ": " + image.message);
  }
  image.format = PNG_FORMAT_RGB;
  Screenshot shot;
  shot.width = static_cast<int>(image.width);
  shot.height = static_cast<int>(image.height);
  shot.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, shot.rgb.data(), 0, nullptr)) {
    png_image_free(&image);
    throw std::runtime_error("cannot decode the screenshot " + file.string() + ": " + image.message);
  }
  return shot;
}

bool is_red(int r, int g, int b) { return r > 150 && g < 80 && b < 80; }

int differing_pixels(const Screenshot& a, const Screenshot& b) {
  if (a.width != b.width || a.height != b.height) return a.width * a.height;
  int differing = 0;
  for (size_t p = 0; p + 2 < a.rgb.size(); p += 3) {
    bool differs = false;
    for (int c = 0; c < 3; ++c) differs = differs || std::abs(int(a.rgb[p + c]) - int(b.rgb[p + c])) > 40;
    differing += differs;
  }
  return differing;
}

}  // namespace posekit::testing
