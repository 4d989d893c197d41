// submesh: the kept faces with only their vertices, renumbered in order of first use.
#include <gtest/gtest.h>

#include "posekit/error.hpp"
#include "posekit/submesh.hpp"

namespace posekit {
namespace {

TEST(Submesh, KeepsTheFlaggedFacesAndOnlyTheirVertices) {
  Eigen::MatrixX3d vertices(5, 3);
  vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 2, 2;
  Eigen::MatrixX3i faces(3, 3);
  faces << 0, 1, 2, 1, 3, 2, 3, 4, 1;
  std::vector<int> original;
  const Mesh part = submesh(vertices, faces, {0, 1, 1}, &original);
  EXPECT_EQ(original, (std::vector<int>{1, 3, 2, 4}));
  ASSERT_EQ(part.faces.rows(), 2);
  EXPECT_EQ(part.faces.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(part.faces.row(1), Eigen::RowVector3i(1, 3, 0));
  for (size_t i = 0; i < original.size(); ++i) EXPECT_EQ(part.vertices.row(static_cast<Eigen::Index>(i)), vertices.row(original[i]));
  EXPECT_EQ(submesh(vertices, faces, {0, 0, 0}).vertices.rows(), 0);
}

TEST(Submesh, RejectsFlagsOfAnotherLengthAndBadIndices) {
  Eigen::MatrixX3d vertices = Eigen::MatrixX3d::Zero(3, 3);
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, 1, 2;
  EXPECT_THROW(submesh(vertices, faces, {1, 1}), ArgumentError);
  faces << 0, 1, 3;
  EXPECT_THROW(submesh(vertices, faces, {1}), ArgumentError);
}

}  // namespace
}  // namespace posekit
