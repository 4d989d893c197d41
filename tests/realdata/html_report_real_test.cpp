// HTML reports of real poses: the lion-01 correction at most 3 MB and the whole crane sequence at
// most 60 MB, both opening in headless Chromium with no console error and the frame slider working.
#include "command_runner.hpp"
#include "headless_browser.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace posekit::testing {
namespace {

constexpr double kMegabyte = 1024.0 * 1024.0;

void expect_opens_cleanly(const std::filesystem::path& page, const std::string& fragment = "") {
  const PageState state = load_page(page, fragment);
  EXPECT_EQ(state.status, "ready") << page;
  EXPECT_EQ(state.errors, 0) << page;
  EXPECT_TRUE(state.console_messages.empty()) << page << ": " << state.console_messages.front();
}

TEST(HtmlReportRealPoses, LionCorrectionReportIsSmallAndOpens) {
  if (const std::string reason = browser_unavailable(); !reason.empty()) GTEST_SKIP() << reason;
  POSEKIT_REQUIRE_SHARED_POSE(reference, "lion-poses/lion-reference.obj");
  POSEKIT_REQUIRE_SHARED_POSE(target, "lion-poses/lion-01.obj");
  TemporaryDirectory outputs;
  const std::filesystem::path page = outputs.path() / "lion-01.html";
  const CommandResult run = run_posekit({"correct", reference.string(), target.string(), "-o",
                                         (outputs.path() / "lion-01.obj").string(), "--device", "cpu", "--html", page.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_LE(static_cast<double>(std::filesystem::file_size(page)), 3.0 * kMegabyte);
  expect_opens_cleanly(page);
  const Screenshot shot = screenshot(page);
  EXPECT_GT(shot.count(is_red), 50) << "lion-01's intersecting faces are not red";
}

TEST(HtmlReportRealPoses, CraneSequenceReportIsUnder60MegabytesAndOpens) {
  if (const std::string reason = browser_unavailable(); !reason.empty()) GTEST_SKIP() << reason;
  POSEKIT_REQUIRE_SHARED_POSE(reference, "crane-sequence/crane-0014.obj");
  TemporaryDirectory outputs;
  const std::filesystem::path list = outputs.path() / "frames.txt";
  {
    std::ofstream stream(list);
    for (int frame = 0; frame < 175; ++frame) {
      char name[48];
      std::snprintf(name, sizeof name, "crane-sequence/crane-%04d.obj", frame);
      const std::optional<std::filesystem::path> file = shared_pose(name);
      if (!file) GTEST_SKIP() << "the crane sequence is not in the shared data (" << name << ")";
      stream << file->string() << "\n";
    }
  }
  const std::filesystem::path page = outputs.path() / "crane.html";
  const CommandResult run = run_posekit({"correct-sequence", reference.string(), "--frames-from", list.string(), "-o",
                                         (outputs.path() / "frames").string(), "--device", "cpu", "--html", page.string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  EXPECT_LE(static_cast<double>(std::filesystem::file_size(page)), 60.0 * kMegabyte);
  expect_opens_cleanly(page, "#frame=140");
  const Screenshot early = screenshot(page, "#frame=0");
  const Screenshot late = screenshot(page, "#frame=140");
  EXPECT_GT(differing_pixels(early, late), early.width * early.height / 200);
}

}  // namespace
}  // namespace posekit::testing
