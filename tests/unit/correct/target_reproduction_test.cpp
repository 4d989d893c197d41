#include "correct/target_reproduction.hpp"

#include "two_sheets.hpp"

#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <gtest/gtest.h>

namespace posekit::detail {
namespace {

// A strip of n quads (2n triangles) along x: vertex 2i at (i, 0), vertex 2i + 1 at (i, 1).
Eigen::MatrixX3i strip_faces(int n) {
  Eigen::MatrixX3i faces(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    faces.row(2 * i) << 2 * i, 2 * i + 2, 2 * i + 1;
    faces.row(2 * i + 1) << 2 * i + 1, 2 * i + 2, 2 * i + 3;
  }
  return faces;
}

TEST(CorrectionWeights, OneNearTheCorrectedVerticesZeroFarAndSmoothBetween) {
  const int n = 20;
  const AdjacencyLists neighbours = vertex_neighbours(strip_faces(n), 2 * n + 2);
  std::vector<char> corrected(2 * n + 2, 0);
  corrected[0] = corrected[1] = 1;  // the left end
  const Eigen::VectorXd weights = correction_weights(corrected, neighbours, 2, 3);
  // Ring distance of column i from the left end is i (the diagonal makes the top vertex one ring
  // closer for odd rows, so compare the bottom row, vertex 2i, which is i rings away).
  for (int i = 0; i <= 2; ++i) EXPECT_DOUBLE_EQ(weights(2 * i), 1.0) << i;
  for (int i = 3; i <= 5; ++i) {
    EXPECT_GT(weights(2 * i), 0.0) << i;
    EXPECT_LT(weights(2 * i), 1.0) << i;
    EXPECT_LT(weights(2 * i), weights(2 * i - 2)) << i;
  }
  for (int i = 6; i <= n; ++i) EXPECT_DOUBLE_EQ(weights(2 * i), 0.0) << i;
}

TEST(CorrectionWeights, NothingCorrectedMeansTheTargetEverywhere) {
  const AdjacencyLists neighbours = vertex_neighbours(strip_faces(5), 12);
  const Eigen::VectorXd weights = correction_weights(std::vector<char>(12, 0), neighbours, 3, 3);
  EXPECT_EQ(weights.size(), 12);
  EXPECT_DOUBLE_EQ(weights.maxCoeff(), 0.0);
}

TEST(CorrectionWeights, RejectsBadArguments) {
  const AdjacencyLists neighbours = vertex_neighbours(strip_faces(5), 12);
  EXPECT_THROW(correction_weights(std::vector<char>(11, 0), neighbours, 3, 3), ArgumentError);
  EXPECT_THROW(correction_weights(std::vector<char>(12, 0), neighbours, -1, 3), ArgumentError);
  EXPECT_THROW(correction_weights(std::vector<char>(12, 0), neighbours, 3, -1), ArgumentError);
}

TEST(BlendTowardsTarget, InterpolatesRowByRow) {
  Eigen::MatrixX3d integrated(3, 3);
  integrated << 1, 1, 1, 2, 2, 2, 3, 3, 3;
  const Eigen::MatrixX3d target = Eigen::MatrixX3d::Zero(3, 3);
  const Eigen::VectorXd weights = Eigen::Vector3d(1.0, 0.5, 0.0);
  const Eigen::MatrixX3d blended = blend_towards_target(integrated, target, weights);
  EXPECT_TRUE(blended.row(0).isApprox(integrated.row(0)));
  EXPECT_TRUE(blended.row(1).isApprox(Eigen::RowVector3d(1, 1, 1)));
  EXPECT_TRUE(blended.row(2).isZero());
  EXPECT_THROW(blend_towards_target(integrated, target, Eigen::VectorXd::Ones(2)), ArgumentError);
}

// The target's dent goes through the bottom sheet; the result keeps the top sheet flat. Blended
// towards the target from nothing kept, the dent would intersect, so the result is kept around it,
// a ring more each round, until the blend adds no intersection; the rest takes the target's place.
TEST(ReproduceTarget, KeepsTheResultWhereTheTargetWouldIntersect) {
  const TwoSheets sheets = two_sheets(21);
  const Eigen::MatrixX3d result = sheets.vertices;
  const Eigen::MatrixX3d target = dented(sheets, 0.3) + Eigen::MatrixX3d::Constant(sheets.vertices.rows(), 3, 0.01);
  ASSERT_FALSE(self_intersecting_faces(target, sheets.faces).empty());
  const AdjacencyLists neighbours = vertex_neighbours(sheets.faces, static_cast<int>(result.rows()));
  const FaceTest new_faces = [&](const Eigen::MatrixX3d& pose) { return self_intersecting_faces(pose, sheets.faces); };
  ReproductionSettings settings;
  settings.blend_rings = 2;
  settings.widening_rings = 1;
  settings.attempts = 12;
  const Reproduction reproduction =
      reproduce_target(result, target, std::vector<char>(result.rows(), 0), sheets.faces, neighbours, settings,
                       new_faces, {});
  ASSERT_TRUE(reproduction.pose);
  const Eigen::MatrixX3d& pose = *reproduction.pose;
  EXPECT_TRUE(self_intersecting_faces(pose, sheets.faces).empty());
  const int middle = sheets.top(10, 10);
  EXPECT_EQ(pose.row(middle), result.row(middle));
  EXPECT_EQ(pose.row(0), target.row(0));
  EXPECT_EQ(pose.row(sheets.top(0, 0)), target.row(sheets.top(0, 0)));
  EXPECT_GT(reproduction.reproduced_vertices, static_cast<int>(result.rows()) / 2);
  EXPECT_LT(reproduction.reproduced_vertices, static_cast<int>(result.rows()));

  // One attempt cannot get there: nothing is blended.
  settings.attempts = 1;
  EXPECT_FALSE(reproduce_target(result, target, std::vector<char>(result.rows(), 0), sheets.faces, neighbours,
                                settings, new_faces, {})
                   .pose);
}

}  // namespace
}  // namespace posekit::detail
