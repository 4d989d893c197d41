// posekit deform and posekit register as users run them: files in, files out, one-line errors.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <posekit/demo_shape.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/submesh.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "command_runner.hpp"
#include "test_data.hpp"

namespace posekit::testing {
namespace {

// Demo-arm examples at 0, 45, 90 and 135 degrees in a temporary folder, and the 67.5-degree pose.
struct BlendFiles : ::testing::Test {
  void SetUp() override {
    DemoArmOptions options;
    options.ring_segments = 16;
    options.bend_angles_degrees = {45.0, 90.0, 135.0};
    const PoseSet poses = make_demo_arm(options);
    for (int k = 0; k < poses.pose_count(); ++k) {
      examples.push_back((folder.path() / ("example-" + std::to_string(k) + ".obj")).string());
      write_mesh(examples.back(), poses.mesh(k));
    }
    faces = poses.faces();
    options.bend_angles_degrees = {67.5, 60.0};
    const PoseSet targets = make_demo_arm(options);
    truth = targets.pose(1);
    bent60 = targets.pose(2);
    output_folder = folder.path() / "out";
    std::filesystem::create_directory(output_folder);
  }

  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path path = folder.path() / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }

  // "VERTEX X Y Z" lines for the vertices of `pose`, with a comment and a blank line.
  std::string constraint_text(const Eigen::MatrixX3d& pose, const std::vector<int>& vertices) const {
    std::ostringstream text;
    text.precision(17);
    text << "# vertex x y z\n\n";
    for (int v : vertices) text << v << " " << pose(v, 0) << " " << pose(v, 1) << " " << pose(v, 2) << "\n";
    return text.str();
  }

  std::vector<std::string> deform_arguments(const std::string& constraints, const std::string& output) const {
    std::vector<std::string> arguments{"deform", "--examples"};
    arguments.insert(arguments.end(), examples.begin(), examples.end());
    arguments.insert(arguments.end(), {"--constraints", constraints, "-o", output});
    return arguments;
  }

  bool output_empty() const { return std::filesystem::is_empty(output_folder); }

  TemporaryDirectory folder;
  std::filesystem::path output_folder;
  std::vector<std::string> examples;
  Eigen::MatrixX3i faces;
  Eigen::MatrixX3d truth;
  Eigen::MatrixX3d bent60;
  const std::vector<int> points{0, 50, 100, 150, 200, 250, 300, 350, 400, 433};
};

double distortion(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b, const Eigen::MatrixX3i& faces) {
  return (a - b).rowwise().norm().maxCoeff() / std::sqrt(face_areas(b, faces).sum());
}

TEST_F(BlendFiles, DeformWritesThePoseAndAReport) {
  const std::string constraints = write("c.txt", constraint_text(truth, points));
  const std::string output = (output_folder / "pose.off").string();
  const std::string report = (output_folder / "report.json").string();
  std::vector<std::string> arguments = deform_arguments(constraints, output);
  arguments.insert(arguments.end(), {"--report", report});
  const CommandResult result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_NE(result.out.find("10 constraints, 4 examples"), std::string::npos) << result.out;
  const Mesh pose = read_mesh(output);
  EXPECT_EQ(pose.faces, faces);
  EXPECT_LT(distortion(pose.vertices, truth, faces), 0.02);
  std::ifstream stream(report);
  const nlohmann::json json = nlohmann::json::parse(stream);
  EXPECT_EQ(json["constraints"], 10);
  EXPECT_EQ(json["reference"], examples.front());
  EXPECT_EQ(json["setup"]["atoms"]["full"], 4 * 20 * 4);
  EXPECT_GT(json["deformation"]["iterations"].size(), 2u);
  EXPECT_EQ(json["deformation"]["iterations"][0]["stage"], "initial");
  EXPECT_LT(json["constraint_residual"]["max"].get<double>(), 1e-3);
  EXPECT_GT(json["seconds"]["deformation"].get<double>(), 0.0);
}

TEST_F(BlendFiles, DeformWithTheSkeletonDictionaryWritesAndReusesItsSkinningCache) {
  const std::string constraints = write("c.txt", constraint_text(truth, points));
  const std::string output = (output_folder / "pose.obj").string();
  const std::string report = (output_folder / "report.json").string();
  const std::string cache = (output_folder / "skinning.txt").string();
  std::vector<std::string> arguments = deform_arguments(constraints, output);
  arguments.insert(arguments.end(), {"--dictionary", "skeleton", "--skinning-cache", cache, "--report", report});
  CommandResult result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  ASSERT_TRUE(std::filesystem::exists(cache));
  EXPECT_LT(distortion(read_mesh(output).vertices, truth, faces), 0.03);
  nlohmann::json json = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(json["setup"]["dictionary"], "skeleton");
  const int bones = json["setup"]["bones"].get<int>();
  EXPECT_GE(bones, 2);
  EXPECT_EQ(json["deformation"]["iterations"].back()["stage"].get<std::string>().rfind("skeleton ", 0), 0u);
  const auto written = std::filesystem::last_write_time(cache);
  // The second run reads the cache instead of decomposing again.
  result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_EQ(std::filesystem::last_write_time(cache), written);
  json = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(json["setup"]["bones"].get<int>(), bones);
  // Another example set with the same cache: one line naming the cache, nothing written.
  std::filesystem::remove(output);
  std::vector<std::string> fewer = {"deform", "--examples", examples[0], examples[1], examples[2], "--constraints",
                                    constraints, "-o", output, "--dictionary", "skeleton", "--skinning-cache", cache};
  result = run_posekit(fewer);
  EXPECT_EQ(result.exit_status, 1);
  EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
  EXPECT_NE(result.err.find("skinning.txt:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("other example poses"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(output));
}

TEST_F(BlendFiles, DeformRefusesDictionaryOptionsThatCannotWork) {
  const std::string constraints = write("c.txt", constraint_text(truth, points));
  const std::string output = (output_folder / "pose.obj").string();
  const auto refused = [&](std::vector<std::string> extra, const std::string& expected,
                           std::vector<std::string> arguments) {
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const CommandResult result = run_posekit(arguments);
    EXPECT_EQ(result.exit_status, 1) << result.err;
    EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
    EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
  };
  // A skeleton from one example: there is no motion to learn bones from.
  refused({"--dictionary", "skeleton"}, "needs at least two",
          {"deform", "--examples", examples[0], "--constraints", constraints, "-o", output});
  refused({"--dictionary", "skeleton", "--weights", write("w.txt", "1\n")}, "--weights",
          deform_arguments(constraints, output));
  refused({"--dictionary", "skeleton", "--bones", "100000"}, "--bones 100000", deform_arguments(constraints, output));
  refused({"--skinning-cache", (output_folder / "s.txt").string()}, "--dictionary skeleton or auto",
          deform_arguments(constraints, output));
  refused({"--dictionary", "skeleton", "--skinning-cache", write("bad.txt", "hello\n")}, "bad.txt:1:",
          deform_arguments(constraints, output));
  EXPECT_TRUE(output_empty());
}

TEST_F(BlendFiles, DeformMatchesGroupedFeaturesAutomatically) {
  // The last two constraints (a vertex half way along the first bone and the far tip) are listed with
  // each other's positions, in one group.
  std::string text = constraint_text(truth, {0, 50, 100, 150, 200, 250, 300, 350});
  std::ostringstream swapped;
  swapped.precision(17);
  swapped << "55 " << truth(433, 0) << " " << truth(433, 1) << " " << truth(433, 2) << " ends\n";
  swapped << "433 " << truth(55, 0) << " " << truth(55, 1) << " " << truth(55, 2) << " ends\n";
  const std::string constraints = write("c.txt", text + swapped.str());
  const std::string output = (output_folder / "pose.obj").string();
  const std::string report = (output_folder / "report.json").string();
  std::vector<std::string> arguments = deform_arguments(constraints, output);
  arguments.insert(arguments.end(), {"--report", report});
  const CommandResult result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  std::ifstream stream(report);
  const nlohmann::json json = nlohmann::json::parse(stream);
  EXPECT_EQ(json["correspondence"]["assignments"], 2);
  EXPECT_EQ(json["correspondence"]["chosen"], 1);
  EXPECT_EQ(json["correspondence"]["vertices"][8], 433);
  EXPECT_LT(distortion(read_mesh(output).vertices, truth, faces), 0.03);
}

TEST_F(BlendFiles, DeformInterpolatesToASecondConstraintSet) {
  const std::string first = write("a.txt", constraint_text(truth, points));
  const std::string second = write("b.txt", constraint_text(bent60, {5, 60, 120, 433}));
  std::vector<std::string> arguments = deform_arguments(first, (output_folder / "walk.obj").string());
  arguments.insert(arguments.end(), {"--to", second, "--frames", "3"});
  const CommandResult result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  for (const char* name : {"walk-000.obj", "walk-001.obj", "walk-002.obj"}) {
    EXPECT_TRUE(std::filesystem::exists(output_folder / name)) << name;
  }
  EXPECT_LT(distortion(read_mesh(output_folder / "walk-000.obj").vertices, truth, faces), 0.02);
  EXPECT_FALSE(std::filesystem::exists(output_folder / "walk.obj"));
}

TEST_F(BlendFiles, DeformRejectsBadConstraintFilesWithTheLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"# header\n1 0 0 0\n434 1 2 3\n", "c.txt:3: vertex index 434 is outside [0, 434)"},
      {"1 0 0 0\n2 0 nan 0\n", "c.txt:2: y 'nan' is not finite"},
      {"1 0 0 0\n2 0 0\n", "c.txt:2: expected 'VERTEX X Y Z [GROUP]', found 3 fields"},
      {"one 0 0 0\n", "c.txt:1: 'one' is not a vertex index"},
      {"\n# nothing here\n", "c.txt: the file lists no constraint"},
  };
  for (const auto& [text, fragment] : cases) {
    const std::string constraints = write("c.txt", text);
    const CommandResult result = run_posekit(deform_arguments(constraints, (output_folder / "pose.obj").string()));
    EXPECT_EQ(result.exit_status, 1) << text;
    ASSERT_EQ(result.err_lines().size(), 1u) << result.err;
    EXPECT_NE(result.err.find(fragment), std::string::npos) << result.err;
    EXPECT_TRUE(output_empty()) << text;
  }
}

TEST_F(BlendFiles, DeformRejectsADegenerateReference) {
  Mesh degenerate = read_mesh(examples.front());
  degenerate.vertices.row(degenerate.faces(7, 2)) = degenerate.vertices.row(degenerate.faces(7, 0));
  const std::string flat = (folder.path() / "flat.obj").string();
  write_mesh(flat, degenerate);
  std::vector<std::string> arguments{"deform", "--examples", flat, examples[1], "--constraints",
                                     write("c.txt", constraint_text(truth, points)), "-o",
                                     (output_folder / "pose.obj").string()};
  const CommandResult result = run_posekit(arguments);
  EXPECT_EQ(result.exit_status, 1);
  // Reading warns about the degenerate face; then one error line.
  const std::vector<std::string> lines = result.err_lines();
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(std::count_if(lines.begin(), lines.end(),
                          [](const std::string& line) { return line.rfind("posekit: error: ", 0) == 0; }),
            1)
      << result.err;
  EXPECT_NE(lines.back().find("flat.obj: cannot serve as the reference pose"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("zero area"), std::string::npos) << result.err;
  EXPECT_TRUE(output_empty());
}

TEST_F(BlendFiles, DeformRejectsOtherBadInput) {
  const std::string constraints = write("c.txt", constraint_text(truth, points));
  const std::string output = (output_folder / "pose.obj").string();
  // An example of another connectivity.
  DemoArmOptions other;
  other.ring_segments = 20;
  other.bend_angles_degrees = {};
  const std::string odd = (folder.path() / "odd.obj").string();
  write_mesh(odd, make_demo_arm(other).mesh(0));
  CommandResult result = run_posekit({"deform", "--examples", examples[0], odd, "--constraints", constraints, "-o", output});
  EXPECT_EQ(result.exit_status, 1);
  EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
  EXPECT_NE(result.err.find("odd.obj"), std::string::npos) << result.err;
  // A weight file with the wrong number of rows.
  std::vector<std::string> arguments = deform_arguments(constraints, output);
  arguments.insert(arguments.end(), {"--weights", write("w.txt", "1 0\n0 1\n")});
  result = run_posekit(arguments);
  EXPECT_EQ(result.exit_status, 1);
  EXPECT_NE(result.err.find("w.txt: has 2 weight rows for 434 vertices"), std::string::npos) << result.err;
  // An output format posekit does not write: refused before any work.
  result = run_posekit(deform_arguments(constraints, (output_folder / "pose.stl").string()));
  EXPECT_EQ(result.exit_status, 1);
  EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
  // No example at all is a usage error.
  result = run_posekit({"deform", "--examples", "--constraints", constraints, "-o", output});
  EXPECT_EQ(result.exit_status, 2) << result.err;
  EXPECT_TRUE(output_empty());
}

// The 60-degree pose without the far end of its second bone, as an OFF scan, and 6 features.
struct ScanFiles : BlendFiles {
  void SetUp() override {
    BlendFiles::SetUp();
    const Mesh rest = read_mesh(examples.front());
    std::vector<char> kept(static_cast<size_t>(faces.rows()), 0);
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const double x = (rest.vertices(faces(f, 0), 0) + rest.vertices(faces(f, 1), 0) + rest.vertices(faces(f, 2), 0)) / 3;
      kept[static_cast<size_t>(f)] = x <= 3.2;
    }
    const Mesh scan_mesh = submesh(bent60, faces, kept, &original);
    scan = (folder.path() / "scan.off").string();
    write_mesh(scan, scan_mesh);
    features = write("features.txt", constraint_text(bent60, {0, 60, 120, 180, 240, 300}));
  }
  std::vector<std::string> register_arguments(const std::string& feature_file, const std::string& output) const {
    std::vector<std::string> arguments{"register", "--examples"};
    arguments.insert(arguments.end(), examples.begin(), examples.end());
    arguments.insert(arguments.end(), {"--scan", scan, "--features", feature_file, "-o", output});
    return arguments;
  }
  std::vector<int> original;
  std::string scan;
  std::string features;
};

TEST_F(ScanFiles, RegisterCompletesTheScanAndReportsCorrespondences) {
  const std::string output = (output_folder / "full.ply").string();
  const std::string report = (output_folder / "report.json").string();
  std::vector<std::string> arguments = register_arguments(features, output);
  arguments.insert(arguments.end(), {"--report", report, "--icp-iterations", "6"});
  const CommandResult result = run_posekit(arguments);
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const Mesh full = read_mesh(output);
  EXPECT_EQ(full.faces, faces);
  // The missing end of the arm is completed to within a few percent of the square root of the area.
  EXPECT_LT(distortion(full.vertices, bent60, faces), 0.06);
  std::ifstream stream(report);
  const nlohmann::json json = nlohmann::json::parse(stream);
  ASSERT_EQ(json["correspondence_of_scan_vertices"]["mesh_vertex"].size(), original.size());
  EXPECT_EQ(json["icp"].size(), 6u);
  const double length = std::sqrt(face_areas(bent60, faces).sum());
  size_t good = 0;
  for (size_t i = 0; i < original.size(); ++i) {
    const int matched = json["correspondence_of_scan_vertices"]["mesh_vertex"][i];
    good += (bent60.row(matched) - bent60.row(original[i])).norm() < 0.05 * length;
  }
  EXPECT_GT(good, 0.98 * original.size());
}

TEST_F(ScanFiles, RegisterRejectsBadInput) {
  const std::string output = (output_folder / "full.obj").string();
  CommandResult result = run_posekit(register_arguments(write("f.txt", "3 0 0 0\n9999 1 1 1\n"), output));
  EXPECT_EQ(result.exit_status, 1);
  ASSERT_EQ(result.err_lines().size(), 1u) << result.err;
  EXPECT_NE(result.err.find("f.txt:2: vertex index 9999 is outside [0, 434)"), std::string::npos) << result.err;
  const std::string bad_scan = write("scan.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  std::vector<std::string> arguments = register_arguments(features, output);
  arguments[arguments.size() - 5] = bad_scan;
  result = run_posekit(arguments);
  EXPECT_EQ(result.exit_status, 1);
  EXPECT_EQ(result.err_lines().size(), 1u) << result.err;
  EXPECT_NE(result.err.find("scan.obj"), std::string::npos) << result.err;
  EXPECT_TRUE(output_empty());
}

TEST(BlendCli, CommandsHaveHelp) {
  for (const char* command : {"deform", "register"}) {
    const CommandResult result = run_posekit({command, "--help"});
    EXPECT_EQ(result.exit_status, 0) << command;
    EXPECT_NE(result.out.find("--examples"), std::string::npos) << command;
  }
}

}  // namespace
}  // namespace posekit::testing
