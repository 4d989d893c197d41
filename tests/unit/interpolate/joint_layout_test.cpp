// Joints as strips around part boundaries and rigid pieces shrunk to overlap them by one strip.
#include "interpolate/joint_layout.hpp"
#include "interpolation_fixtures.hpp"

#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <set>

namespace posekit::testing {
namespace {

class JointLayoutOfTwoParts : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    arm_ = demo_arm({}, 16);
    parts_.resize(arm_.faces().rows());
    for (int f = 0; f < arm_.faces().rows(); ++f) {
      double x = 0.0;
      for (int c = 0; c < 3; ++c) x += arm_.pose(0)(arm_.faces()(f, c), 0) / 3.0;
      parts_(f) = x < 2.0 ? 0 : 1;
    }
    edges_ = edge_map(arm_.faces());
    incident_ = edge_faces(edges_);
    layout_ = interpolation::build_joint_layout(arm_.faces(), parts_, edges_, incident_,
                                                vertex_neighbours(arm_.faces(), arm_.vertex_count()), GetParam());
  }
  PoseSet arm_;
  Eigen::VectorXi parts_;
  EdgeMap edges_;
  AdjacencyLists incident_;
  interpolation::JointLayout layout_;
};

TEST_P(JointLayoutOfTwoParts, StripsCoverTheBoundaryAndPiecesOverlapThemByOne) {
  const int width = GetParam();
  ASSERT_EQ(layout_.joints.size(), 1u) << "one ring-shaped joint around the middle";
  ASSERT_EQ(layout_.rigid_pieces.size(), 2u);
  std::vector<int> holders(static_cast<size_t>(arm_.faces().rows()), 0);
  std::set<int> joint_faces(layout_.joints[0].faces.begin(), layout_.joints[0].faces.end());
  for (const auto& piece : layout_.rigid_pieces) {
    for (const int f : piece.faces) ++holders[static_cast<size_t>(f)];
  }
  for (const int f : layout_.joints[0].faces) ++holders[static_cast<size_t>(f)];
  for (int f = 0; f < arm_.faces().rows(); ++f) {
    const int strip = layout_.face_strip(f);
    const bool in_joint = joint_faces.count(f) > 0;
    EXPECT_EQ(in_joint, strip >= 1 && strip <= width) << "face " << f << " strip " << strip;
    // Strip `width` is the overlap; every face is somewhere.
    EXPECT_EQ(holders[static_cast<size_t>(f)], strip == width ? 2 : 1) << "face " << f << " strip " << strip;
  }
  EXPECT_EQ(layout_.joint_face_count, static_cast<int>(joint_faces.size()));
  // The joint is width strips on each side: 2 * width rings of faces around a 16-segment tube.
  EXPECT_NEAR(static_cast<double>(joint_faces.size()), 2.0 * width * 2 * 16, 2.0 * 16);
}

TEST_P(JointLayoutOfTwoParts, PiecesKeepToTheirPart) {
  for (const auto& piece : layout_.rigid_pieces) {
    std::set<int> labels;
    for (const int f : piece.faces) labels.insert(parts_(f));
    EXPECT_EQ(labels.size(), 1u);
  }
  if (GetParam() >= 2) {
    // Shrunk by width - 1 strips, the two pieces no longer share a vertex.
    std::set<int> first(layout_.rigid_pieces[0].vertices.begin(), layout_.rigid_pieces[0].vertices.end());
    for (const int v : layout_.rigid_pieces[1].vertices) EXPECT_EQ(first.count(v), 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Widths, JointLayoutOfTwoParts, ::testing::Values(1, 2, 3, 5));

TEST(JointLayout, OnePartHasNoJoint) {
  const PoseSet arm = demo_arm({}, 8);
  const EdgeMap edges = edge_map(arm.faces());
  const interpolation::JointLayout layout = interpolation::build_joint_layout(
      arm.faces(), Eigen::VectorXi::Zero(arm.faces().rows()), edges, edge_faces(edges),
      vertex_neighbours(arm.faces(), arm.vertex_count()), 3);
  EXPECT_TRUE(layout.joints.empty());
  ASSERT_EQ(layout.rigid_pieces.size(), 1u);
  EXPECT_EQ(static_cast<int>(layout.rigid_pieces[0].faces.size()), arm.faces().rows());
}

TEST(JointLayout, RejectsBadWidthOrLabels) {
  const PoseSet arm = demo_arm({}, 8);
  const EdgeMap edges = edge_map(arm.faces());
  const AdjacencyLists neighbours = vertex_neighbours(arm.faces(), arm.vertex_count());
  EXPECT_THROW(interpolation::build_joint_layout(arm.faces(), Eigen::VectorXi::Zero(arm.faces().rows()), edges,
                                                 edge_faces(edges), neighbours, 0),
               ArgumentError);
  EXPECT_THROW(interpolation::build_joint_layout(arm.faces(), Eigen::VectorXi::Zero(3), edges, edge_faces(edges),
                                                 neighbours, 3),
               ArgumentError);
}

}  // namespace
}  // namespace posekit::testing
