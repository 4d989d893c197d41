// Self-intersections of the real poses: the counts published with the data and, face by face,
// agreement with CGAL::Polygon_mesh_processing::self_intersections. Skipped when the data is absent.
#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include "cgal_reference.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

namespace posekit {
namespace {

struct PublishedCount {
  const char* file;
  size_t faces;
};

void PrintTo(const PublishedCount& count, std::ostream* out) { *out << count.file << ": " << count.faces; }

class PublishedSelfIntersectionCount : public ::testing::TestWithParam<PublishedCount> {};

TEST_P(PublishedSelfIntersectionCount, Matches) {
  POSEKIT_REQUIRE_SHARED_POSE(file, GetParam().file);
  const Mesh mesh = read_mesh(file);
  EXPECT_EQ(self_intersecting_faces(mesh.vertices, mesh.faces).size(), GetParam().faces);
}

// The counts in the data's README.md.
INSTANTIATE_TEST_SUITE_P(SharedData, PublishedSelfIntersectionCount,
                         ::testing::Values(PublishedCount{"lion-poses/lion-reference.obj", 148},
                                           PublishedCount{"lion-poses/lion-01.obj", 495},
                                           PublishedCount{"lion-poses/lion-04.obj", 756},
                                           PublishedCount{"lion-poses/lion-07.obj", 941},
                                           PublishedCount{"cat-poses/cat-reference.obj", 75},
                                           PublishedCount{"cat-poses/cat-04.obj", 1030},
                                           PublishedCount{"cat-poses/cat-07.obj", 1399},
                                           PublishedCount{"horse-poses/horse-07.obj", 108},
                                           PublishedCount{"horse-poses/horse-09.obj", 0},
                                           PublishedCount{"horse-poses/horse-10.obj", 0}),
                         [](const ::testing::TestParamInfo<PublishedCount>& info) {
                           std::string name = std::filesystem::path(info.param.file).stem().string();
                           for (char& c : name) if (c == '-') c = '_';
                           return name;
                         });

TEST(SelfIntersectionsOnRealData, LionPoseAddsIntersectionsToItsReference) {
  POSEKIT_REQUIRE_SHARED_POSE(reference_file, "lion-poses/lion-reference.obj");
  POSEKIT_REQUIRE_SHARED_POSE(pose_file, "lion-poses/lion-01.obj");
  const Mesh reference = read_mesh(reference_file);
  const Mesh pose = read_mesh(pose_file);
  const std::vector<int> reference_faces = self_intersecting_faces(reference.vertices, reference.faces);
  const std::vector<int> pose_faces = self_intersecting_faces(pose.vertices, pose.faces);
  EXPECT_EQ(new_intersecting_faces(pose_faces, reference_faces).size(), 357u);
  EXPECT_TRUE(new_intersecting_faces(reference_faces, reference_faces).empty());
}

TEST(SelfIntersectionsOnRealData, ElephantPosesStayInThePublishedRange) {
  if (!::posekit::testing::shared_pose("elephant-poses/elephant-01.obj")) {
    GTEST_SKIP() << "shared pose data not found: elephant-poses";
  }
  for (int i = 1; i <= 10; ++i) {
    const std::string relative = "elephant-poses/elephant-" + std::string(i < 10 ? "0" : "") + std::to_string(i) + ".obj";
    const auto file = ::posekit::testing::shared_pose(relative);
    ASSERT_TRUE(file.has_value()) << relative;
    const Mesh mesh = read_mesh(*file);
    const size_t count = self_intersecting_faces(mesh.vertices, mesh.faces).size();
    EXPECT_GE(count, 683u) << relative;
    EXPECT_LE(count, 1959u) << relative;
  }
}

std::vector<std::string> every_shared_pose() {
  std::vector<std::string> files;
  const auto add = [&files](const std::string& folder, const std::string& stem, int first, int last) {
    for (int i = first; i <= last; ++i) {
      files.push_back(folder + "/" + stem + "-" + (i < 10 ? "0" : "") + std::to_string(i) + ".obj");
    }
  };
  files.emplace_back("lion-poses/lion-reference.obj");
  add("lion-poses", "lion", 1, 9);
  files.emplace_back("cat-poses/cat-reference.obj");
  add("cat-poses", "cat", 1, 9);
  add("horse-poses", "horse", 1, 10);
  add("elephant-poses", "elephant", 1, 10);
  return files;
}

class MatchesCgalOnRealPose : public ::testing::TestWithParam<std::string> {};

// Every pose of the data is a polygon mesh, so CGAL's function applies to all of them; a pose that
// is not is skipped with the reason.
TEST_P(MatchesCgalOnRealPose, SameFaces) {
  POSEKIT_REQUIRE_SHARED_POSE(file, GetParam());
  const Mesh mesh = read_mesh(file);
  const auto expected = ::posekit::testing::cgal_self_intersecting_faces(mesh.vertices, mesh.faces);
  if (!expected) GTEST_SKIP() << GetParam() << " is not a polygon mesh; CGAL's function cannot take it";
  EXPECT_EQ(self_intersecting_faces(mesh.vertices, mesh.faces), *expected);
}

INSTANTIATE_TEST_SUITE_P(SharedData, MatchesCgalOnRealPose, ::testing::ValuesIn(every_shared_pose()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = std::filesystem::path(info.param).stem().string();
                           for (char& c : name) if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace posekit
