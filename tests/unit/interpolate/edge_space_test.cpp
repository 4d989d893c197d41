// Edge-space coordinates of pose sets and the hinges of a patch: the dihedral angle of a hinge and
// its gradient, against the geometry functions and central differences.
#include "interpolate/edge_space_patch.hpp"
#include "interpolation_fixtures.hpp"
#include "test_data.hpp"

#include <posekit/edge_space.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace posekit::testing {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(WrapAngle, MovesIntoMinusPiToPi) {
  EXPECT_DOUBLE_EQ(wrap_angle(0.5), 0.5);
  EXPECT_NEAR(wrap_angle(0.5 + 2.0 * kPi), 0.5, 1e-12);
  EXPECT_NEAR(wrap_angle(-0.5 - 4.0 * kPi), -0.5, 1e-12);
  EXPECT_NEAR(std::abs(wrap_angle(3.0 * kPi)), kPi, 1e-12);
}

TEST(EdgeSpaceCoordinates, LengthsAndAnglesOfEveryPose) {
  const PoseSet arm = demo_arm({60.0, 120.0});
  const EdgeMap edges = edge_map(arm.faces());
  const AdjacencyLists incident = edge_faces(edges);
  const EdgeSpaceCoordinates coordinates = edge_space_coordinates(arm, edges, incident);
  ASSERT_EQ(coordinates.edge_count(), edges.edges.rows());
  ASSERT_EQ(coordinates.pose_count(), 3);
  for (int k = 0; k < 3; ++k) {
    const Eigen::VectorXd lengths = edge_lengths(arm.pose(k), edges.edges);
    const Eigen::VectorXd angles = dihedral_angles(arm.pose(k), arm.faces(), edges, incident);
    EXPECT_TRUE(matrices_near(coordinates.lengths.col(k), lengths, 0.0, 1e-15));
    for (int e = 0; e < coordinates.edge_count(); ++e) {
      ASSERT_TRUE(coordinates.hinge[static_cast<size_t>(e)]) << "the closed arm has no boundary edge";
      // Unwrapped: within pi of pose 0, and the same angle up to whole turns.
      EXPECT_LE(std::abs(coordinates.angles(e, k) - coordinates.angles(e, 0)), kPi + 1e-12);
      EXPECT_NEAR(wrap_angle(coordinates.angles(e, k) - angles(e)), 0.0, 1e-12);
    }
  }
  Eigen::VectorXd weights(3);
  weights << 0.2, 0.3, 0.5;
  EXPECT_TRUE(matrices_near(coordinates.combined_lengths(weights), coordinates.lengths * weights, 0.0, 1e-15));
}

TEST(EdgeSpaceCoordinates, BoundaryAndDegenerateFacesHaveNoHinge) {
  // Two triangles of a square and a third one, degenerate in the second pose, hanging off one side.
  Eigen::MatrixX3i faces(3, 3);
  faces << 0, 1, 2, 0, 2, 3, 1, 4, 2;
  PoseSet poses(faces);
  Eigen::MatrixX3d first(5, 3);
  first << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0.5, 0.5;
  Eigen::MatrixX3d second = first;
  second.row(4) << 1, 0.5, 0;  // on the line through vertices 1 and 2
  poses.add_pose(first);
  poses.add_pose(second);
  const EdgeMap edges = edge_map(faces);
  const EdgeSpaceCoordinates coordinates = edge_space_coordinates(poses, edges, edge_faces(edges));
  EXPECT_EQ(coordinates.degenerate_face, (std::vector<char>{0, 0, 1}));
  int hinges = 0;
  for (int e = 0; e < coordinates.edge_count(); ++e) {
    const bool is_diagonal = edges.edges(e, 0) == 0 && edges.edges(e, 1) == 2;
    EXPECT_EQ(coordinates.hinge[static_cast<size_t>(e)] != 0, is_diagonal) << "edge " << e;
    EXPECT_EQ(std::isnan(coordinates.angles(e, 1)), !is_diagonal);
    hinges += coordinates.hinge[static_cast<size_t>(e)];
  }
  EXPECT_EQ(hinges, 1);
}

TEST(EdgeSpaceCoordinates, RejectsForeignEdgeMaps) {
  const PoseSet arm = demo_arm({30.0});
  const PoseSet other = demo_arm({30.0}, 16);
  const EdgeMap edges = edge_map(other.faces());
  EXPECT_THROW(edge_space_coordinates(arm, edges, edge_faces(edges)), ArgumentError);
  EXPECT_THROW(edge_space_coordinates(PoseSet(arm.faces()), edges, edge_faces(edges)), ArgumentError);
}

class PatchHinges : public ::testing::Test {
 protected:
  void SetUp() override {
    arm_ = demo_arm({75.0});
    edges_ = edge_map(arm_.faces());
    incident_ = edge_faces(edges_);
    coordinates_ = edge_space_coordinates(arm_, edges_, incident_);
    // Every other face: a patch with boundaries and edges of one face only.
    std::vector<int> faces(static_cast<size_t>(arm_.faces().rows()) / 2);
    std::iota(faces.begin(), faces.end(), 0);
    patch_ = interpolation::make_edge_space_patch(faces, arm_.faces(), arm_.vertex_count(), edges_, incident_,
                                                  coordinates_.hinge);
  }
  Eigen::MatrixX3d local(int pose) const {
    Eigen::MatrixX3d x(patch_.vertex_count(), 3);
    for (int v = 0; v < patch_.vertex_count(); ++v) x.row(v) = arm_.pose(pose).row(patch_.vertices[static_cast<size_t>(v)]);
    return x;
  }
  PoseSet arm_;
  EdgeMap edges_;
  AdjacencyLists incident_;
  EdgeSpaceCoordinates coordinates_;
  interpolation::EdgeSpacePatch patch_;
};

TEST_F(PatchHinges, AnglesMatchTheMesh) {
  ASSERT_GT(patch_.hinge_count(), 0);
  EXPECT_LT(patch_.hinge_count(), patch_.edge_count()) << "the patch's rim has no hinges";
  const Eigen::MatrixX3d x = local(1);
  for (int h = 0; h < patch_.hinge_count(); ++h) {
    const int mesh_edge = patch_.mesh_hinges[static_cast<size_t>(h)];
    EXPECT_NEAR(wrap_angle(interpolation::hinge_angle(patch_.hinges[static_cast<size_t>(h)], x) -
                           coordinates_.angles(mesh_edge, 1)),
                0.0, 1e-12);
  }
  for (int e = 0; e < patch_.edge_count(); ++e) {
    const int mesh_edge = patch_.mesh_edges[static_cast<size_t>(e)];
    EXPECT_NEAR((x.row(patch_.edges(e, 1)) - x.row(patch_.edges(e, 0))).norm(), coordinates_.lengths(mesh_edge, 1), 1e-12);
  }
}

TEST_F(PatchHinges, GradientMatchesCentralDifferences) {
  Eigen::MatrixX3d x = local(1);
  const double step = 1e-6;
  for (int h = 0; h < patch_.hinge_count(); h += 97) {
    const interpolation::Hinge& hinge = patch_.hinges[static_cast<size_t>(h)];
    const Eigen::Matrix<double, 4, 3> gradient = interpolation::hinge_angle_gradient(hinge, x);
    const int corners[4] = {hinge.a, hinge.b, hinge.c, hinge.d};
    for (int i = 0; i < 4; ++i) {
      for (int c = 0; c < 3; ++c) {
        const double saved = x(corners[i], c);
        x(corners[i], c) = saved + step;
        const double up = interpolation::hinge_angle(hinge, x);
        x(corners[i], c) = saved - step;
        const double down = interpolation::hinge_angle(hinge, x);
        x(corners[i], c) = saved;
        const double numeric = wrap_angle(up - down) / (2.0 * step);
        EXPECT_NEAR(gradient(i, c), numeric, 1e-5 * (1.0 + std::abs(numeric))) << "hinge " << h << " corner " << i;
      }
    }
  }
}

}  // namespace
}  // namespace posekit::testing
