// The command line as users and other tools see it: exit status, one-line errors, files left behind.
#include <posekit/correct.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

#include "command_runner.hpp"
#include "test_data.hpp"

namespace posekit::testing {
namespace {

struct MalformedCase {
  std::string file;
  std::string fragment;
};

std::vector<MalformedCase> malformed_cases() {
  std::vector<MalformedCase> cases;
  std::ifstream table(project_test_data() / "malformed" / "cases.tsv");
  std::string line;
  while (std::getline(table, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t tab = line.find('\t');
    if (tab == std::string::npos) continue;
    cases.push_back({line.substr(0, tab), line.substr(tab + 1)});
  }
  return cases;
}

class MalformedInput : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedInput, ConvertFailsWithOneLineAndWritesNothing) {
  const MalformedCase& malformed = GetParam();
  const std::string input = (project_test_data() / "malformed" / malformed.file).string();
  TemporaryDirectory output_folder;
  const std::string output = (output_folder.path() / "out.obj").string();

  const CommandResult result = run_posekit({"convert", input, "-o", output});
  EXPECT_EQ(result.exit_status, 1) << result.err;
  const std::vector<std::string> lines = result.err_lines();
  ASSERT_EQ(lines.size(), 1u) << result.err;
  EXPECT_NE(lines[0].find(malformed.file), std::string::npos) << "error does not name the file: " << lines[0];
  EXPECT_NE(lines[0].find(malformed.fragment), std::string::npos) << lines[0];
  EXPECT_TRUE(folder_contents(output_folder.path()).empty()) << "an output or temporary file was left";
}

TEST_P(MalformedInput, CheckFailsWithOneLine) {
  const MalformedCase& malformed = GetParam();
  const std::string input = (project_test_data() / "malformed" / malformed.file).string();
  const CommandResult result = run_posekit({"check", input});
  EXPECT_EQ(result.exit_status, 1) << result.err;
  EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
}

std::string case_name(const ::testing::TestParamInfo<MalformedCase>& info) {
  std::string name = info.param.file;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedInput, ::testing::ValuesIn(malformed_cases()), case_name);

TEST(MalformedCorpus, HasAtLeastTwentyCases) { EXPECT_GE(malformed_cases().size(), 20u); }

TEST(Cli, EverySubcommandHasHelp) {
  for (const char* command : {"devices", "check", "convert", "generate", "demo", "correct", "correct-sequence", "interpolate"}) {
    const CommandResult result = run_posekit({command, "--help"});
    EXPECT_EQ(result.exit_status, 0) << command << ": " << result.err;
    EXPECT_NE(result.out.find("Usage"), std::string::npos) << command;
  }
}

TEST(Cli, UsageErrorIsOneLineWithStatusTwo) {
  for (const std::vector<std::string>& arguments :
       std::vector<std::vector<std::string>>{{"frobnicate"}, {"check"}, {"check", "a.obj", "--bogus"}, {}}) {
    const CommandResult result = run_posekit(arguments);
    EXPECT_EQ(result.exit_status, 2) << result.err;
    EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
  }
}

TEST(Cli, MissingFileNamesIt) {
  const CommandResult result = run_posekit({"check", "/nonexistent/pose.obj"});
  EXPECT_EQ(result.exit_status, 1);
  ASSERT_EQ(result.err_lines().size(), 1u) << result.err;
  EXPECT_NE(result.err.find("/nonexistent/pose.obj"), std::string::npos) << result.err;
}

TEST(Cli, DevicesListsCpuAvailableAndEveryBackend) {
  const CommandResult table = run_posekit({"devices"});
  ASSERT_EQ(table.exit_status, 0) << table.err;
  const CommandResult result = run_posekit({"devices", "--json"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  std::vector<std::string> names;
  for (const nlohmann::json& backend : report.at("backends")) {
    names.push_back(backend.at("name"));
    if (backend.at("name") == "cpu") {
      EXPECT_EQ(backend.at("state"), "available");
      EXPECT_TRUE(backend.at("fp64").get<bool>());
    } else if (backend.at("state") != "available") {
      EXPECT_FALSE(backend.at("reason").get<std::string>().empty()) << backend.dump();
    }
  }
  EXPECT_EQ(names, (std::vector<std::string>{"cuda", "vulkan", "opencl", "cpu"}));
}

TEST(Cli, GeneratedDemoPosesIntersectOnlyWhenBent) {
  TemporaryDirectory folder;
  const CommandResult generated = run_posekit({"generate", "--output-dir", folder.path().string()});
  ASSERT_EQ(generated.exit_status, 0) << generated.err;
  const std::string rest = (folder.path() / "arm-rest.obj").string();
  const CommandResult rest_check = run_posekit({"check", rest, "--json"});
  ASSERT_EQ(rest_check.exit_status, 0) << rest_check.err;
  EXPECT_EQ(nlohmann::json::parse(rest_check.out).at("self_intersecting_faces"), 0);

  int bent_poses = 0;
  for (const auto& file : folder_contents(folder.path())) {
    if (file.filename().string().rfind("arm-bent-", 0) != 0) continue;
    ++bent_poses;
    const CommandResult check = run_posekit({"check", file.string(), "--reference", rest, "--json"});
    ASSERT_EQ(check.exit_status, 0) << check.err;
    EXPECT_EQ(nlohmann::json::parse(check.out).at("faces"),
              nlohmann::json::parse(rest_check.out).at("faces"));
  }
  EXPECT_GE(bent_poses, 1);
}

// A longer arm has more rings along the tube; a length shorter than the joint's blend is refused.
TEST(Cli, GeneratedArmGrowsWithItsLength) {
  TemporaryDirectory standard;
  TemporaryDirectory longer;
  ASSERT_EQ(run_posekit({"generate", "--output-dir", standard.path().string(), "--angles", "90"}).exit_status, 0);
  const CommandResult generated =
      run_posekit({"generate", "--output-dir", longer.path().string(), "--angles", "90", "--length", "12"});
  ASSERT_EQ(generated.exit_status, 0) << generated.err;
  const auto vertices_of = [](const std::filesystem::path& folder) {
    const CommandResult check = run_posekit({"check", (folder / "arm-rest.obj").string(), "--json"});
    EXPECT_EQ(check.exit_status, 0) << check.err;
    return nlohmann::json::parse(check.out).at("vertices").get<int>();
  };
  EXPECT_GT(vertices_of(longer.path()), 2 * vertices_of(standard.path()));

  TemporaryDirectory refused;
  const CommandResult too_short =
      run_posekit({"generate", "--output-dir", refused.path().string(), "--length", "0.5"});
  EXPECT_NE(too_short.exit_status, 0);
  EXPECT_NE(too_short.err.find("--length"), std::string::npos) << too_short.err;
  EXPECT_TRUE(folder_contents(refused.path()).empty());
}

TEST(Cli, CheckCountsLionIntersections) {
  POSEKIT_REQUIRE_SHARED_POSE(target, "lion-poses/lion-01.obj");
  POSEKIT_REQUIRE_SHARED_POSE(reference, "lion-poses/lion-reference.obj");

  const CommandResult alone = run_posekit({"check", target.string(), "--json"});
  ASSERT_EQ(alone.exit_status, 0) << alone.err;
  EXPECT_EQ(nlohmann::json::parse(alone.out).at("self_intersecting_faces"), 495);

  const CommandResult against = run_posekit({"check", target.string(), "--reference", reference.string(), "--json"});
  ASSERT_EQ(against.exit_status, 0) << against.err;
  const nlohmann::json report = nlohmann::json::parse(against.out);
  EXPECT_EQ(report.at("new_self_intersecting_faces"), 357);
  EXPECT_EQ(report.at("reference_self_intersecting_faces"), 148);

  const CommandResult text = run_posekit({"check", reference.string()});
  ASSERT_EQ(text.exit_status, 0) << text.err;
  EXPECT_NE(text.out.find("148 self-intersecting faces"), std::string::npos) << text.out;
}

TEST(Cli, CheckRejectsDifferentConnectivity) {
  POSEKIT_REQUIRE_SHARED_POSE(lion, "lion-poses/lion-01.obj");
  POSEKIT_REQUIRE_SHARED_POSE(cat, "cat-poses/cat-01.obj");
  const CommandResult result = run_posekit({"check", lion.string(), "--reference", cat.string()});
  EXPECT_EQ(result.exit_status, 1);
  ASSERT_EQ(result.err_lines().size(), 1u) << result.err;
  EXPECT_NE(result.err.find("cat-01.obj"), std::string::npos) << result.err;
}

TEST(Cli, ConvertRoundTripKeepsTheMesh) {
  POSEKIT_REQUIRE_SHARED_POSE(lion, "lion-poses/lion-01.obj");
  TemporaryDirectory folder;
  const std::string off = (folder.path() / "lion.off").string();
  const std::string obj = (folder.path() / "lion.obj").string();
  ASSERT_EQ(run_posekit({"convert", lion.string(), "-o", off}).exit_status, 0);
  ASSERT_EQ(run_posekit({"convert", off, "-o", obj}).exit_status, 0);
  const CommandResult check = run_posekit({"check", obj, "--reference", lion.string(), "--json"});
  ASSERT_EQ(check.exit_status, 0) << check.err;
  EXPECT_EQ(nlohmann::json::parse(check.out).at("self_intersecting_faces"), 495);
}

class CorrectCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(run_posekit({"generate", "--output-dir", poses_.path().string(), "--angles", "135"}).exit_status, 0);
    rest_ = (poses_.path() / "arm-rest.obj").string();
    bent_ = (poses_.path() / "arm-bent-135.obj").string();
    output_ = (outputs_.path() / "corrected.obj").string();
  }
  // Nothing may be written when the command fails.
  void expect_failure_without_output(const CommandResult& result, int status) {
    EXPECT_EQ(result.exit_status, status) << result.err;
    EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
    EXPECT_TRUE(folder_contents(outputs_.path()).empty());
  }
  TemporaryDirectory poses_;
  TemporaryDirectory outputs_;
  std::string rest_, bent_, output_;
};

TEST_F(CorrectCommand, CorrectsTheDemoArmAndWritesItsReport) {
  const std::string report_file = (outputs_.path() / "report.json").string();
  const CommandResult result =
      run_posekit({"correct", rest_, bent_, "-o", output_, "--report", report_file, "--progress"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  std::ifstream stream(report_file);
  const nlohmann::json report = nlohmann::json::parse(stream);
  const nlohmann::json& outcome = report.at("result");
  EXPECT_GT(outcome.at("intersecting_faces").at("target").get<int>(), 0);
  EXPECT_EQ(outcome.at("intersecting_faces").at("new"), 0);
  EXPECT_TRUE(outcome.at("distortion").contains("stretched_faces"));
  EXPECT_EQ(outcome.at("distance_to_target").at("median"), 0.0);
  const nlohmann::json& field = report.at("field");
  EXPECT_GT(field.at("centers").get<int>(), 0);
  EXPECT_FALSE(field.at("whole_mesh").get<bool>());
  ASSERT_EQ(field.at("regions").size(), 1u);
  EXPECT_EQ(field.at("regions")[0].at("rk45").at("failures"), 0);
  for (const char* step : {"key_frames", "classification", "fitting", "integration", "reproduction"}) {
    EXPECT_TRUE(field.at("seconds").contains(step)) << step;
  }
  // One entry per stage of the ladder, in its order (a stage may run twice), and one progress line
  // per stage that ran.
  const nlohmann::json& stages = report.at("stages");
  ASSERT_GE(stages.size(), repair_stages().size());
  size_t listed = 0;
  for (size_t k = 0; k < stages.size(); ++k) {
    const nlohmann::json& stage = stages[k];
    if (listed < repair_stages().size() && stage.at("name") == repair_stages()[listed].name) ++listed;
    for (const char* key : {"ran", "skipped", "kept", "new_faces_before", "new_faces_after", "regions", "vertices",
                            "seconds", "note", "details"}) {
      EXPECT_TRUE(stage.contains(key)) << stage.at("name") << " " << key;
    }
  }
  // As many progress lines of each stage as it ran.
  for (const RepairStageInfo& info : repair_stages()) {
    int runs = 0;
    for (const nlohmann::json& stage : stages) runs += stage.at("name") == info.name && stage.at("ran").get<bool>() ? 1 : 0;
    int lines = 0;
    const std::string line = "correct: " + info.name + " (";
    for (size_t at = result.err.find(line); at != std::string::npos; at = result.err.find(line, at + 1)) ++lines;
    EXPECT_EQ(lines, runs) << info.name << "\n" << result.err;
  }
  EXPECT_EQ(listed, repair_stages().size());  // every stage of the list, in its order
  EXPECT_TRUE(stages[0].at("ran").get<bool>());
  EXPECT_TRUE(report.at("seconds").is_number());
  const CommandResult check = run_posekit({"check", output_, "--reference", rest_, "--json"});
  ASSERT_EQ(check.exit_status, 0) << check.err;
  EXPECT_EQ(nlohmann::json::parse(check.out).at("new_self_intersecting_faces"), 0);
}

// --no-<stage> comes from the ladder's stage list; --whole-mesh fits every vertex.
TEST_F(CorrectCommand, StageFlagsAndTheWholeMesh) {
  const std::string report_file = (outputs_.path() / "report.json").string();
  std::vector<std::string> arguments{"correct", rest_, bent_, "-o", output_, "--report", report_file, "--whole-mesh"};
  for (const RepairStageInfo& stage : repair_stages()) {
    if (stage.optional) arguments.push_back("--no-" + stage.name);
  }
  const CommandResult result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  std::ifstream stream(report_file);
  const nlohmann::json report = nlohmann::json::parse(stream);
  EXPECT_TRUE(report.at("field").at("whole_mesh").get<bool>());
  for (const nlohmann::json& stage : report.at("stages")) {
    if (stage.at("name") == "field") continue;
    EXPECT_EQ(stage.at("skipped"), "disabled") << stage.at("name");
  }
}

TEST_F(CorrectCommand, RejectsDifferentConnectivity) {
  TemporaryDirectory coarse;
  ASSERT_EQ(run_posekit({"generate", "--output-dir", coarse.path().string(), "--ring-segments", "16"}).exit_status, 0);
  const std::string other = (coarse.path() / "arm-bent-135.obj").string();
  expect_failure_without_output(run_posekit({"correct", rest_, other, "-o", output_}), 1);
}

TEST_F(CorrectCommand, RejectsAnEmptyExclusionFile) {
  const std::string empty = (poses_.path() / "exclude.txt").string();
  std::ofstream(empty) << "# nothing\n";
  const CommandResult result = run_posekit({"correct", rest_, bent_, "-o", output_, "--exclude", empty});
  expect_failure_without_output(result, 1);
  EXPECT_NE(result.err.find("exclude.txt"), std::string::npos) << result.err;
}

TEST_F(CorrectCommand, RejectsAReferenceWithNan) {
  const std::string nan_file = (project_test_data() / "malformed" / "nan_coordinate.obj").string();
  const CommandResult result = run_posekit({"correct", nan_file, bent_, "-o", output_});
  expect_failure_without_output(result, 1);
  EXPECT_NE(result.err.find("nan_coordinate.obj"), std::string::npos) << result.err;
}

TEST_F(CorrectCommand, RejectsParametersOutOfRange) {
  expect_failure_without_output(run_posekit({"correct", rest_, bent_, "-o", output_, "--key-frames", "1"}), 2);
  expect_failure_without_output(run_posekit({"correct", rest_, bent_, "-o", output_, "--error-factor", "-1"}), 2);
  expect_failure_without_output(run_posekit({"correct", rest_, bent_, "-o", output_, "--intersection-substeps", "0"}), 2);
  expect_failure_without_output(run_posekit({"correct", rest_, bent_, "-o", output_, "--separation-tolerance", "0"}), 2);
  expect_failure_without_output(run_posekit({"correct", rest_, bent_, "-o", output_, "--collar-rings", "0"}), 2);
  expect_failure_without_output(run_posekit({"correct", rest_, bent_, "-o", output_, "--no-field"}), 2);
  expect_failure_without_output(run_posekit({"correct", rest_, bent_, "-o", output_, "--device", "abacus"}), 1);
}

}  // namespace
}  // namespace posekit::testing
