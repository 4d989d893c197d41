#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

std::vector<std::filesystem::path> pose_files(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".obj") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

Mesh triangle_pair() {
  Mesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  mesh.faces.resize(2, 3);
  mesh.faces << 0, 1, 2, 1, 3, 2;
  return mesh;
}

TEST(PoseSet, AddPoseKeepsPosesAndNames) {
  const Mesh mesh = triangle_pair();
  PoseSet poses(mesh.faces);
  EXPECT_EQ(poses.vertex_count(), 0);
  poses.add_pose(mesh.vertices, "first");
  poses.add_pose(mesh.vertices * 2.0, "second");
  EXPECT_EQ(poses.pose_count(), 2);
  EXPECT_EQ(poses.vertex_count(), 4);
  EXPECT_EQ(poses.pose_name(1), "second");
  EXPECT_EQ(poses.pose(1), mesh.vertices * 2.0);
  EXPECT_EQ(poses.mesh(0).faces, mesh.faces);
}

TEST(PoseSet, AddPoseWithAnotherVertexCountThrows) {
  const Mesh mesh = triangle_pair();
  PoseSet poses(mesh.faces);
  poses.add_pose(mesh.vertices, "first");
  const Eigen::MatrixX3d fewer = mesh.vertices.topRows(3);
  EXPECT_THROW(poses.add_pose(fewer, "fewer"), ArgumentError);
  EXPECT_EQ(poses.pose_count(), 1);
}

TEST(PoseSet, FirstPoseMustHoldEveryIndexOfTheFaces) {
  const Mesh mesh = triangle_pair();
  PoseSet poses(mesh.faces);
  const Eigen::MatrixX3d fewer = mesh.vertices.topRows(3);
  EXPECT_THROW(poses.add_pose(fewer, "fewer"), ArgumentError);
  EXPECT_EQ(poses.pose_count(), 0);
}

TEST(CheckSameConnectivity, NamesBothMeshesAndTheFirstDifference) {
  const Mesh a = triangle_pair();
  Mesh b = triangle_pair();
  EXPECT_NO_THROW(check_same_connectivity(a, "a.obj", b, "b.obj"));
  b.faces.row(1) << 1, 2, 3;
  try {
    check_same_connectivity(a, "a.obj", b, "b.obj");
    FAIL() << "different faces were accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "b.obj: face 1 is (1, 2, 3) but in a.obj it is (1, 3, 2) (zero-based vertex indices): the poses must "
              "share one connectivity");
  }
  Mesh c = triangle_pair();
  c.faces.conservativeResize(1, 3);
  EXPECT_THROW(check_same_connectivity(a, "a.obj", c, "c.obj"), InputError);
}

TEST(ReadPoseSet, LionPosesShareOneConnectivity) {
  POSEKIT_REQUIRE_SHARED_POSE(reference, "lion-poses/lion-reference.obj");
  const std::vector<std::filesystem::path> files = pose_files(reference.parent_path());
  ASSERT_EQ(files.size(), 10U);
  std::vector<std::string> warnings;
  const PoseSet poses = read_pose_set(files, &warnings);
  EXPECT_EQ(poses.pose_count(), 10);
  EXPECT_EQ(poses.vertex_count(), 5000);
  EXPECT_EQ(poses.faces().rows(), 9996);
  for (int i = 0; i < poses.pose_count(); ++i) {
    EXPECT_EQ(poses.pose_name(i), files[static_cast<std::size_t>(i)].filename().string());
  }
  const Mesh last = read_mesh(files.back());
  EXPECT_TRUE(poses.pose(9) == last.vertices);
  EXPECT_TRUE(poses.faces() == last.faces);
}

TEST(ReadPoseSet, LionAndCatDoNotMix) {
  POSEKIT_REQUIRE_SHARED_POSE(lion, "lion-poses/lion-01.obj");
  POSEKIT_REQUIRE_SHARED_POSE(cat, "cat-poses/cat-01.obj");
  try {
    read_pose_set({lion, cat});
    FAIL() << "a lion and a cat were read as one pose set";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(lion.string()), std::string::npos) << message;
    EXPECT_NE(message.find(cat.string()), std::string::npos) << message;
    EXPECT_NE(message.find("7207 vertices"), std::string::npos) << message;
    EXPECT_NE(message.find("5000"), std::string::npos) << message;
  }
}

TEST(ReadPoseSet, AMalformedFileIsReportedByName) {
  const std::filesystem::path good = testing::project_test_data() / "valid" / "tetrahedron.obj";
  const std::filesystem::path bad = testing::project_test_data() / "malformed" / "quad_face.obj";
  try {
    read_pose_set({good, bad, good});
    FAIL() << "a malformed file was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), bad.string());
  }
}

TEST(ReadPoseSet, NoFilesIsAnArgumentError) { EXPECT_THROW(read_pose_set({}), ArgumentError); }

}  // namespace
}  // namespace posekit
