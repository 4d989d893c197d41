// posekit correct-sequence as a user runs it: every frame written under its own name with the
// report, an interrupted run resumed to the same files, bad input refused with one line and nothing
// written.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "command_runner.hpp"
#include "test_data.hpp"

namespace posekit::testing {
namespace {

namespace fs = std::filesystem;

std::string file_bytes(const fs::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << stream.rdbuf();
  return bytes.str();
}

std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class CorrectSequenceCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    // The arm bending through itself from the fourth frame to the eighth (70 degrees and more) and back.
    const std::vector<std::string> angles = {"30", "45", "60", "70", "75", "80", "78", "72", "65", "50", "35"};
    std::vector<std::string> arguments = {"generate", "--output-dir", poses_.path().string(), "--angles"};
    arguments.insert(arguments.end(), angles.begin(), angles.end());
    ASSERT_EQ(run_posekit(arguments).exit_status, 0);
    rest_ = (poses_.path() / "arm-rest.obj").string();
    std::ofstream list(poses_.path() / "frames.txt");
    for (const std::string& angle : angles) {
      const std::string name = "arm-bent-" + std::string(3 - angle.size(), '0') + angle + ".obj";
      frames_.push_back((poses_.path() / name).string());
      names_.push_back(name);
      list << name << "\n";
    }
    std::sort(names_.begin(), names_.end());
  }
  std::vector<std::string> command(const fs::path& folder) const {
    std::vector<std::string> arguments = {"correct-sequence", rest_};
    arguments.insert(arguments.end(), frames_.begin(), frames_.end());
    arguments.insert(arguments.end(), {"-o", folder.string()});
    return arguments;
  }
  TemporaryDirectory poses_;
  TemporaryDirectory outputs_;
  std::string rest_;
  std::vector<std::string> frames_;
  std::vector<std::string> names_;  // sorted
};

TEST_F(CorrectSequenceCommand, WritesEveryFrameUnderItsNameWithTheReport) {
  const fs::path folder = outputs_.path() / "corrected";
  const fs::path report_file = outputs_.path() / "sequence.json";
  std::vector<std::string> arguments = command(folder);
  arguments.insert(arguments.end(), {"--report", report_file.string(), "--progress"});
  const CommandResult result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_EQ(names_in(folder), names_);  // the frames only: the kept corrections are gone
  EXPECT_NE(result.err.find("11/11 frames"), std::string::npos) << result.err;
  std::ifstream stream(report_file);
  const nlohmann::json report = nlohmann::json::parse(stream);
  const nlohmann::json& sequence = report.at("sequence");
  EXPECT_EQ(sequence.at("frames"), 11);
  EXPECT_EQ(sequence.at("corrected_frames"), 5);
  EXPECT_EQ(sequence.at("frames_with_new_faces"), 0);
  EXPECT_LT(sequence.at("coherence").at("largest_offset_change").get<double>(),
            sequence.at("coherence").at("largest_offset_change_alone").get<double>());
  ASSERT_EQ(report.at("frames").size(), 11u);
  for (const nlohmann::json& frame : report.at("frames")) {
    EXPECT_EQ(frame.at("new_faces"), 0) << frame.at("name");
    EXPECT_FALSE(frame.at("reused").get<bool>());
    // A frame corrected by itself has its correction's report; one that carried its predecessor's has none.
    const bool own = frame.at("corrected").get<bool>() && !frame.at("carried").get<bool>();
    EXPECT_EQ(frame.contains("correction"), own) << frame.at("name");
  }
  EXPECT_GE(sequence.at("carried_frames").get<int>(), 1);
  const CommandResult check = run_posekit({"check", (folder / "arm-bent-080.obj").string(), "--reference", rest_, "--json"});
  ASSERT_EQ(check.exit_status, 0) << check.err;
  EXPECT_EQ(nlohmann::json::parse(check.out).at("new_self_intersecting_faces"), 0);
}

TEST_F(CorrectSequenceCommand, ResumesAnInterruptedRunToTheSameFrames) {
  const fs::path whole = outputs_.path() / "whole";
  ASSERT_EQ(run_posekit(command(whole)).exit_status, 0);

  const fs::path folder = outputs_.path() / "resumed";
  const fs::path partial = folder / ".posekit-partial";
  const std::vector<std::string> from_list = {"correct-sequence", rest_, "--frames-from",
                                              (poses_.path() / "frames.txt").string(), "-o", folder.string()};
  // Killed as soon as the first frame's own correction is kept.
  const CommandResult interrupted = run_posekit_until(from_list, [&] {
    std::error_code error;
    for (fs::directory_iterator entry(partial, error), end; !error && entry != end; entry.increment(error)) {
      if (entry->path().extension() == ".ply") return true;
    }
    return false;
  });
  ASSERT_EQ(interrupted.exit_status, 137) << "the run ended before it could be interrupted: " << interrupted.err;
  EXPECT_EQ(names_in(folder), std::vector<std::string>{".posekit-partial"});  // no frame half-written

  std::vector<std::string> resume = from_list;
  const fs::path report_file = outputs_.path() / "resumed.json";
  resume.insert(resume.end(), {"--resume", "--report", report_file.string()});
  const CommandResult resumed = run_posekit(resume);
  ASSERT_EQ(resumed.exit_status, 0) << resumed.err;
  std::ifstream stream(report_file);
  const nlohmann::json report = nlohmann::json::parse(stream);
  int reused = 0;
  for (const nlohmann::json& frame : report.at("frames")) reused += frame.at("reused").get<bool>() ? 1 : 0;
  EXPECT_GE(reused, 1);
  EXPECT_EQ(names_in(folder), names_);
  for (const std::string& name : names_) EXPECT_EQ(file_bytes(folder / name), file_bytes(whole / name)) << name;
}

TEST_F(CorrectSequenceCommand, RefusesBadInputWithOneLineAndWritesNothing) {
  const fs::path folder = outputs_.path() / "corrected";
  TemporaryDirectory coarse;
  ASSERT_EQ(run_posekit({"generate", "--output-dir", coarse.path().string(), "--ring-segments", "16"}).exit_status, 0);
  const std::string other = (coarse.path() / "arm-bent-090.obj").string();
  const std::string missing = (poses_.path() / "arm-bent-999.obj").string();
  const fs::path blocker = outputs_.path() / "a-file";
  std::ofstream(blocker) << "not a folder\n";
  struct Case {
    std::vector<std::string> arguments;
    std::string named;
  };
  std::vector<Case> cases;
  std::vector<std::string> arguments = command(folder);
  arguments.insert(arguments.begin() + 4, other);
  cases.push_back({arguments, other});
  arguments = command(folder);
  arguments.insert(arguments.begin() + 4, missing);
  cases.push_back({arguments, missing});
  cases.push_back({command(blocker / "corrected"), (blocker / "corrected").string()});
  for (const Case& c : cases) {
    const CommandResult result = run_posekit(c.arguments);
    EXPECT_EQ(result.exit_status, 1) << result.err;
    ASSERT_EQ(result.err_lines().size(), 1u) << result.err;
    EXPECT_NE(result.err.find(c.named), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(folder)) << result.err;
  }
}

}  // namespace
}  // namespace posekit::testing
