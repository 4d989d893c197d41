// HTML reports as a person sees them: written by the commands, opened in headless Chromium, checked
// by their final DOM and by screenshots.
#include "command_runner.hpp"
#include "headless_browser.hpp"
#include "test_data.hpp"

#include <posekit/mesh_io.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace posekit::testing {
namespace {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

// Lit grey mesh pixels: the panels drew something.
bool is_shaded_grey(int r, int g, int b) {
  const int high = std::max({r, g, b});
  const int low = std::min({r, g, b});
  return high - low < 30 && high > 50 && high < 235;
}

void expect_opens_cleanly(const std::filesystem::path& page, const std::string& fragment = "") {
  const PageState state = load_page(page, fragment);
  EXPECT_EQ(state.status, "ready") << page;
  EXPECT_EQ(state.errors, 0) << page;
  EXPECT_TRUE(state.console_messages.empty()) << page << ": " << state.console_messages.front();
}

class HtmlReport : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const std::string reason = browser_unavailable(); !reason.empty()) GTEST_SKIP() << reason;
    const CommandResult generated =
        run_posekit({"generate", "--output-dir", poses_.path().string(), "--angles", "30", "60", "90", "120", "135"});
    ASSERT_EQ(generated.exit_status, 0) << generated.err;
  }
  std::string pose(const std::string& name) const { return (poses_.path() / ("arm-" + name + ".obj")).string(); }
  std::filesystem::path output(const std::string& name) const { return outputs_.path() / name; }

  TemporaryDirectory poses_;
  TemporaryDirectory outputs_;
};

TEST_F(HtmlReport, CorrectionOfAnIntersectingPoseShowsItsFacesInRed) {
  const CommandResult run = run_posekit({"correct", pose("rest"), pose("bent-135"), "-o", output("fixed.obj").string(),
                                         "--html", output("report.html").string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  expect_opens_cleanly(output("report.html"));
  const Screenshot shot = screenshot(output("report.html"));
  EXPECT_GT(shot.count(is_shaded_grey), shot.width * shot.height / 50) << "the panels show no mesh";
  EXPECT_GT(shot.count(is_red), 50) << "the target's intersecting faces are not red";
  // The page carries the data it shows: three panels, the stage table, the moved regions.
  const std::string page = read_text(output("report.html"));
  EXPECT_NE(page.find("\"posekit_report\":1"), std::string::npos);
  EXPECT_NE(page.find("\"title\":\"result\""), std::string::npos);
  EXPECT_NE(page.find("\"repair stages\""), std::string::npos);
}

TEST_F(HtmlReport, CleanTargetShowsNoRed) {
  const CommandResult run = run_posekit({"correct", pose("rest"), pose("bent-030"), "-o", output("clean.obj").string(),
                                         "--html", output("clean.html").string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  expect_opens_cleanly(output("clean.html"));
  const Screenshot shot = screenshot(output("clean.html"));
  EXPECT_GT(shot.count(is_shaded_grey), shot.width * shot.height / 50) << "the panels show no mesh";
  EXPECT_EQ(shot.count(is_red), 0);
}

TEST_F(HtmlReport, SequenceFrameSliderChangesThePicture) {
  const CommandResult run = run_posekit({"correct-sequence", pose("rest"), pose("bent-030"), pose("bent-060"), pose("bent-090"),
                                         pose("bent-120"), pose("bent-135"), "-o", output("frames").string(), "--html",
                                         output("sequence.html").string()});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  expect_opens_cleanly(output("sequence.html"), "#frame=4");
  const Screenshot first = screenshot(output("sequence.html"), "#frame=0");
  const Screenshot last = screenshot(output("sequence.html"), "#frame=4");
  EXPECT_GT(differing_pixels(first, last), first.width * first.height / 200);
  EXPECT_EQ(first.count(is_red), 0) << "the 30-degree frame does not intersect";
  EXPECT_GT(last.count(is_red), 50) << "the 135-degree frame's intersecting faces are not red";
}

TEST_F(HtmlReport, InterpolationDeformationAndRegistrationReportsOpen) {
  const CommandResult interpolated = run_posekit({"interpolate", pose("rest"), pose("bent-090"), "--weights", "0.5",
                                                  "-o", output("mid.obj").string(), "--html", output("mid.html").string()});
  ASSERT_EQ(interpolated.exit_status, 0) << interpolated.err;
  expect_opens_cleanly(output("mid.html"));

  std::ofstream(output("constraints.txt")) << "0 0 0 0\n";
  const CommandResult deformed =
      run_posekit({"deform", "--examples", pose("rest"), pose("bent-090"), "--constraints", output("constraints.txt").string(),
                   "-o", output("deformed.obj").string(), "--html", output("deformed.html").string()});
  ASSERT_EQ(deformed.exit_status, 0) << deformed.err;
  expect_opens_cleanly(output("deformed.html"));
  EXPECT_NE(read_text(output("deformed.html")).find("\"markers\""), std::string::npos);

  // The 60-degree pose as the scan, three of its vertices as features.
  const Mesh scan = read_mesh(pose("bent-060"));
  {
    std::ofstream features(output("features.txt"));
    for (const int v : {0, 1000, 2000}) {
      features << v << " " << scan.vertices(v, 0) << " " << scan.vertices(v, 1) << " " << scan.vertices(v, 2) << "\n";
    }
  }
  const CommandResult registered =
      run_posekit({"register", "--examples", pose("rest"), pose("bent-090"), "--scan", pose("bent-060"), "--features",
                   output("features.txt").string(), "-o", output("registered.obj").string(), "--html",
                   output("registered.html").string()});
  ASSERT_EQ(registered.exit_status, 0) << registered.err;
  expect_opens_cleanly(output("registered.html"));
  const std::string page = read_text(output("registered.html"));
  EXPECT_NE(page.find("\"points\""), std::string::npos);
  EXPECT_NE(page.find("\"markers\""), std::string::npos);
}

TEST_F(HtmlReport, IsNotWrittenWhenTheJobFails) {
  // Another connectivity: the command fails on its input, and neither the pose nor the page is left.
  TemporaryDirectory coarse;
  ASSERT_EQ(run_posekit({"generate", "--output-dir", coarse.path().string(), "--ring-segments", "16"}).exit_status, 0);
  const CommandResult failed =
      run_posekit({"correct", pose("rest"), (coarse.path() / "arm-bent-135.obj").string(), "-o",
                   output("fixed.obj").string(), "--html", output("report.html").string()});
  EXPECT_EQ(failed.exit_status, 1);
  EXPECT_EQ(failed.err_lines().size(), 1u) << failed.err;
  EXPECT_TRUE(folder_contents(outputs_.path()).empty());

  // A page that could not be written is named before any work, and nothing is written.
  const CommandResult nowhere =
      run_posekit({"correct", pose("rest"), pose("bent-135"), "-o", output("fixed.obj").string(), "--html",
                   (outputs_.path() / "missing" / "report.html").string()});
  EXPECT_EQ(nowhere.exit_status, 1);
  ASSERT_EQ(nowhere.err_lines().size(), 1u) << nowhere.err;
  EXPECT_NE(nowhere.err.find("--html"), std::string::npos) << nowhere.err;
  EXPECT_NE(nowhere.err.find("missing"), std::string::npos) << nowhere.err;
  EXPECT_TRUE(folder_contents(outputs_.path()).empty());
}

}  // namespace
}  // namespace posekit::testing
