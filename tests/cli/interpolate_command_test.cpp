// posekit interpolate as users call it: outputs and report, the weight syntax, label files, and one
// clear line with no output for every kind of bad input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <posekit/mesh_io.hpp>

#include <fstream>

#include "command_runner.hpp"
#include "test_data.hpp"

namespace posekit::testing {
namespace {

class InterpolateCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const CommandResult generated = run_posekit(
        {"generate", "--output-dir", poses_.path().string(), "--angles", "40", "80", "--ring-segments", "16"});
    ASSERT_EQ(generated.exit_status, 0) << generated.err;
    rest_ = (poses_.path() / "arm-rest.obj").string();
    bent_ = (poses_.path() / "arm-bent-040.obj").string();
    more_ = (poses_.path() / "arm-bent-080.obj").string();
  }
  std::string out(const std::string& name) const { return (outputs_.path() / name).string(); }
  std::vector<std::string> output_files() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(outputs_.path())) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  // A failure: the status, one line on stderr that mentions `fragment`, and nothing written.
  void expect_failure(const std::vector<std::string>& arguments, int status, const std::string& fragment) {
    const CommandResult result = run_posekit(arguments);
    EXPECT_EQ(result.exit_status, status) << result.err;
    ASSERT_EQ(result.err_lines().size(), 1u) << result.err;
    EXPECT_NE(result.err.find(fragment), std::string::npos) << result.err;
    EXPECT_TRUE(output_files().empty()) << "an output was left behind";
  }
  TemporaryDirectory poses_;
  TemporaryDirectory outputs_;
  std::string rest_, bent_, more_;
};

TEST_F(InterpolateCommand, SeveralWeightsGiveSeveralOutputsAndOneReport) {
  const CommandResult result = run_posekit({"interpolate", rest_, bent_, "--weights", "0.25", "0.5", "0.75", "-o",
                                            out("mid-{}.obj"), "--report", out("report.json")});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_EQ(output_files(), (std::vector<std::string>{"mid-0.obj", "mid-1.obj", "mid-2.obj", "report.json"}));
  const Mesh rest = read_mesh(rest_);
  const Mesh middle = read_mesh(out("mid-1.obj"));
  EXPECT_EQ(middle.faces, rest.faces);
  std::ifstream stream(out("report.json"));
  const nlohmann::json report = nlohmann::json::parse(stream);
  EXPECT_EQ(report.at("method"), "mixit");
  EXPECT_GT(report.at("segmentation").at("joints").get<int>(), 0);
  EXPECT_GT(report.at("precomputation_seconds").at("total").get<double>(), 0.0);
  ASSERT_EQ(report.at("outputs").size(), 3u);
  const nlohmann::json& second = report.at("outputs").at(1);
  EXPECT_EQ(second.at("weights"), (nlohmann::json{0.5, 0.5}));
  EXPECT_EQ(second.at("file"), out("mid-1.obj"));
  for (const char* measure : {"edge_length_relative", "dihedral_degrees"}) {
    for (const char* statistic : {"max", "p99.9", "p99"}) {
      EXPECT_GE(second.at("error").at(measure).at(statistic).get<double>(), 0.0) << measure << " " << statistic;
    }
  }
  EXPECT_LT(second.at("error").at("edge_length_relative").at("p99").get<double>(), 0.05);
  for (const char* stage : {"blend", "joints", "alignment", "stitching", "refinement", "projection", "placement", "total"}) {
    EXPECT_TRUE(second.at("seconds").contains(stage)) << stage;
  }
  EXPECT_NE(result.out.find("mid-2.obj"), std::string::npos) << result.out;
}

TEST_F(InterpolateCommand, WeightVectorsForThreePosesAndEveryMethod) {
  for (const char* method : {"mixit", "edge", "vertex"}) {
    const std::string file = out(std::string(method) + ".off");
    const CommandResult result =
        run_posekit({"interpolate", rest_, bent_, more_, "--weights", "0.2,0.3,0.5", "-o", file, "--method", method});
    ASSERT_EQ(result.exit_status, 0) << method << ": " << result.err;
    EXPECT_EQ(read_mesh(file).vertices.rows(), read_mesh(rest_).vertices.rows());
  }
  // Weight 0 is the first pose.
  ASSERT_EQ(run_posekit({"interpolate", rest_, bent_, "--weights", "0", "-o", out("first.obj")}).exit_status, 0);
  EXPECT_LT((read_mesh(out("first.obj")).vertices - read_mesh(rest_).vertices).cwiseAbs().maxCoeff(), 1e-6);
}

TEST_F(InterpolateCommand, SavedSegmentationReadsBackToTheSameResult) {
  ASSERT_EQ(run_posekit({"interpolate", rest_, bent_, "--weights", "0.5", "-o", out("auto.obj"), "--save-segmentation",
                         out("parts.txt")})
                .exit_status,
            0);
  const CommandResult again =
      run_posekit({"interpolate", rest_, bent_, "--weights", "0.5", "-o", out("given.obj"), "--segmentation", out("parts.txt")});
  ASSERT_EQ(again.exit_status, 0) << again.err;
  EXPECT_EQ(read_mesh(out("given.obj")).vertices, read_mesh(out("auto.obj")).vertices);
}

TEST_F(InterpolateCommand, WeightsNotSummingToOneAreAUsageError) {
  expect_failure({"interpolate", rest_, bent_, more_, "--weights", "0.5,0.6,0.1", "-o", out("x.obj")}, 2, "sum to 1.2");
  expect_failure({"interpolate", rest_, bent_, more_, "--weights", "0.5", "-o", out("x.obj")}, 2, "1 entry for 3 poses");
  expect_failure({"interpolate", rest_, bent_, "--weights", "half", "-o", out("x.obj")}, 2, "'half'");
  expect_failure({"interpolate", rest_, bent_, "--weights", "0.2", "0.4", "-o", out("x.obj")}, 2, "{}");
  expect_failure({"interpolate", rest_, "--weights", "1", "-o", out("x.obj")}, 2, "POSE");
}

TEST_F(InterpolateCommand, OptionsOutOfRangeAreAUsageError) {
  expect_failure({"interpolate", rest_, bent_, "--weights", "0.5", "-o", out("x.obj"), "--joint-width", "0"}, 2, "--joint-width");
  expect_failure({"interpolate", rest_, bent_, "--weights", "0.5", "-o", out("x.obj"), "--method", "spline"}, 2, "--method");
  expect_failure({"interpolate", rest_, bent_, "--weights", "0.5", "-o", out("x.obj"), "--rigidity-angle", "0"}, 2,
                 "--rigidity-angle");
}

TEST_F(InterpolateCommand, BadInputFilesNameTheFile) {
  TemporaryDirectory coarse;
  ASSERT_EQ(run_posekit({"generate", "--output-dir", coarse.path().string(), "--angles", "40", "--ring-segments", "8"}).exit_status, 0);
  const std::string other = (coarse.path() / "arm-bent-040.obj").string();
  expect_failure({"interpolate", rest_, other, "--weights", "0.5", "-o", out("x.obj")}, 1, "arm-bent-040.obj");
  const std::string nan_file = (project_test_data() / "malformed" / "nan_coordinate.obj").string();
  expect_failure({"interpolate", nan_file, bent_, "--weights", "0.5", "-o", out("x.obj")}, 1, "nan_coordinate.obj");
  const std::string labels = (poses_.path() / "labels.txt").string();
  std::ofstream(labels) << "0 1 1 0\n";
  expect_failure({"interpolate", rest_, bent_, "--weights", "0.5", "-o", out("x.obj"), "--segmentation", labels}, 1,
                 "labels.txt: 4 part ids");
  expect_failure({"interpolate", rest_, bent_, "--weights", "0.5", "-o", out("x.stl")}, 1, "x.stl");
}

TEST_F(InterpolateCommand, HelpExplainsTheWeights) {
  const CommandResult result = run_posekit({"interpolate", "--help"});
  EXPECT_EQ(result.exit_status, 0);
  EXPECT_NE(result.out.find("(1 - t) * POSE0 + t * POSE1"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("0.25,0.25,0.25,0.25"), std::string::npos) << result.out;
}

}  // namespace
}  // namespace posekit::testing
