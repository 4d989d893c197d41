// Automatic segmentation into rigid parts, connected parts, and part label files.
#include "interpolation_fixtures.hpp"
#include "test_data.hpp"

#include <posekit/error.hpp>
#include <posekit/rigid_segmentation.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

namespace posekit::testing {
namespace {

// The label most faces of `faces` carry, and how many carry it.
std::pair<int, int> majority(const Eigen::VectorXi& labels, const std::vector<int>& faces) {
  std::map<int, int> counts;
  for (const int f : faces) ++counts[labels(f)];
  std::pair<int, int> best{-1, 0};
  for (const auto& [label, count] : counts) {
    if (count > best.second) best = {label, count};
  }
  return best;
}

std::vector<int> faces_with_centre_x(const PoseSet& arm, double low, double high) {
  std::vector<int> faces;
  for (int f = 0; f < arm.faces().rows(); ++f) {
    double x = 0.0;
    for (int c = 0; c < 3; ++c) x += arm.pose(0)(arm.faces()(f, c), 0) / 3.0;
    if (x > low && x < high) faces.push_back(f);
  }
  return faces;
}

TEST(SegmentRigidParts, SeparatesTheBonesOfABentArm) {
  const PoseSet arm = demo_arm({90.0});
  const Eigen::VectorXi parts = segment_rigid_parts(arm);
  ASSERT_EQ(parts.size(), arm.faces().rows());
  const std::vector<int> upper = faces_with_centre_x(arm, -1.0, 1.2);
  const std::vector<int> lower = faces_with_centre_x(arm, 2.8, 5.0);
  const auto [upper_label, upper_count] = majority(parts, upper);
  const auto [lower_label, lower_count] = majority(parts, lower);
  EXPECT_NE(upper_label, lower_label);
  EXPECT_GE(upper_count, static_cast<int>(0.95 * static_cast<double>(upper.size())));
  EXPECT_GE(lower_count, static_cast<int>(0.95 * static_cast<double>(lower.size())));
  // Ids run from 0 and every part is connected.
  EXPECT_EQ(parts.minCoeff(), 0);
  const EdgeMap edges = edge_map(arm.faces());
  EXPECT_EQ(connected_parts(parts, edges, edge_faces(edges)).maxCoeff(), parts.maxCoeff());
}

TEST(SegmentRigidParts, ARigidMotionIsOnePart) {
  PoseSet poses(demo_arm({}).faces());
  poses.add_pose(demo_arm({}).pose(0));
  Eigen::Matrix3d turn = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  poses.add_pose((poses.pose(0) * turn.transpose()).rowwise() + Eigen::RowVector3d(1, -2, 0.5));
  const Eigen::VectorXi parts = segment_rigid_parts(poses);
  EXPECT_EQ(parts.maxCoeff(), 0);
}

TEST(SegmentRigidParts, IsDeterministicAndUsesEveryPose) {
  const PoseSet two = demo_arm({90.0});
  EXPECT_EQ(segment_rigid_parts(two), segment_rigid_parts(two));
  // A third pose that bends the other way splits at least as much.
  const PoseSet three = demo_arm({90.0, -90.0});
  EXPECT_GE(segment_rigid_parts(three).maxCoeff(), segment_rigid_parts(two).maxCoeff());
}

TEST(SegmentRigidParts, RejectsBadInput) {
  const PoseSet arm = demo_arm({90.0});
  PoseSet one(arm.faces());
  one.add_pose(arm.pose(0));
  EXPECT_THROW(segment_rigid_parts(one), ArgumentError);
  SegmentationOptions options;
  options.rigidity_angle_degrees = 0.0;
  EXPECT_THROW(segment_rigid_parts(arm, options), ArgumentError);
  options = SegmentationOptions{};
  options.min_part_fraction = 1.0;
  EXPECT_THROW(segment_rigid_parts(arm, options), ArgumentError);
}

TEST(ConnectedParts, SplitsALabelThatFallsApart) {
  const PoseSet arm = demo_arm({});
  // Label 7 on both ends, 3 in the middle: the two ends become two parts.
  Eigen::VectorXi labels(arm.faces().rows());
  for (int f = 0; f < arm.faces().rows(); ++f) {
    double x = 0.0;
    for (int c = 0; c < 3; ++c) x += arm.pose(0)(arm.faces()(f, c), 0) / 3.0;
    labels(f) = (x < 1.0 || x > 3.0) ? 7 : 3;
  }
  const EdgeMap edges = edge_map(arm.faces());
  const Eigen::VectorXi parts = connected_parts(labels, edges, edge_faces(edges));
  EXPECT_EQ(parts.maxCoeff(), 2);
  EXPECT_EQ(parts(0), 0);
}

TEST(FaceLabels, FromVertexLabelsByMajority) {
  Eigen::MatrixX3i faces(3, 3);
  faces << 0, 1, 2, 2, 3, 4, 0, 3, 4;
  Eigen::VectorXi vertex_labels(5);
  vertex_labels << 5, 5, 1, 9, 2;
  const Eigen::VectorXi labels = face_labels_from_vertex_labels(vertex_labels, faces);
  EXPECT_EQ(labels, (Eigen::VectorXi(3) << 5, 1, 2).finished());
}

class PartLabelFile : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string file = (folder_.path() / name).string();
    std::ofstream(file) << text;
    return file;
  }
  TemporaryDirectory folder_;
  PoseSet arm_ = demo_arm({45.0}, 8);
};

TEST_F(PartLabelFile, ReadsPerFaceAndPerVertexIds) {
  const int faces = static_cast<int>(arm_.faces().rows());
  std::string per_face = "# one per face\n";
  for (int f = 0; f < faces; ++f) per_face += std::to_string(f % 3) + (f % 10 == 9 ? "\n" : " ");
  const Eigen::VectorXi face_labels = read_part_labels(write("faces.txt", per_face), arm_.vertex_count(), arm_.faces());
  ASSERT_EQ(face_labels.size(), faces);
  EXPECT_EQ(face_labels(4), 1);
  std::string per_vertex;
  for (int v = 0; v < arm_.vertex_count(); ++v) per_vertex += (arm_.pose(0)(v, 0) < 2.0 ? "0\n" : "1\n");
  const Eigen::VectorXi from_vertices = read_part_labels(write("vertices.txt", per_vertex), arm_.vertex_count(), arm_.faces());
  ASSERT_EQ(from_vertices.size(), faces);
  EXPECT_EQ(std::set<int>(from_vertices.data(), from_vertices.data() + faces), (std::set<int>{0, 1}));
}

TEST_F(PartLabelFile, WrittenLabelsReadBack) {
  const Eigen::VectorXi labels = segment_rigid_parts(demo_arm({90.0}, 8));
  const std::string file = (folder_.path() / "parts.txt").string();
  write_part_labels(file, labels);
  EXPECT_EQ(read_part_labels(file, arm_.vertex_count(), arm_.faces()), labels);
}

TEST_F(PartLabelFile, WrongCountOrBadIdNamesTheFile) {
  const auto expect_input_error = [&](const std::string& file, const std::string& fragment) {
    try {
      read_part_labels(file, arm_.vertex_count(), arm_.faces());
      ADD_FAILURE() << "no error for " << file;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(file), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
  };
  expect_input_error(write("short.txt", "0 1 2\n"), "3 part ids");
  expect_input_error(write("negative.txt", "0 -1\n"), ":1: part id -1 is outside [0, ");
  expect_input_error(write("word.txt", "0\nleg\n"), ":2: 'leg' is not a part id");
  expect_input_error((folder_.path() / "missing.txt").string(), "cannot open");
}

}  // namespace
}  // namespace posekit::testing
