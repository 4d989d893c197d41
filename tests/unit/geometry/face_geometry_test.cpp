#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace posekit {
namespace {

using ::posekit::testing::matrices_near;

Eigen::MatrixX3d corner_tetrahedron() {
  Eigen::MatrixX3d vertices(4, 3);
  vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return vertices;
}

Eigen::MatrixX3i outward_tetrahedron_faces() {
  Eigen::MatrixX3i faces(4, 3);
  faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return faces;
}

// A pose 3 times the tetrahedron's size against the tetrahedron and its double: 1.5 on every face.
// Moving the apex far out stretches only the three faces that hold it.
TEST(EdgeStretch, IsTheLargestGrowthOfAnEdgeBeyondBothPoses) {
  const Eigen::MatrixX3d first = corner_tetrahedron();
  const Eigen::MatrixX3d second = 2.0 * first;
  const Eigen::MatrixX3i faces = outward_tetrahedron_faces();
  const Eigen::VectorXd scaled = edge_stretch(3.0 * first, first, second, faces);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) EXPECT_NEAR(scaled(f), 1.5, 1e-12);
  EXPECT_NEAR(edge_stretch(first, first, second, faces).maxCoeff(), 0.5, 1e-12);  // shrunk below the double
  Eigen::MatrixX3d pulled = first;
  pulled.row(3) << 0, 0, 10;
  const Eigen::VectorXd stretch = edge_stretch(pulled, first, first, faces);
  EXPECT_NEAR(stretch(0), 1.0, 1e-12);  // the base, without the apex
  EXPECT_NEAR(stretch(1), 10.0, 1e-12);  // the edge from the corner to the apex, 1 long before
  EXPECT_NEAR(stretch(2), 10.0, 1e-12);
  EXPECT_NEAR(stretch(3), std::sqrt(101.0) / std::sqrt(2.0), 1e-12);
  // With a floor of 2 every edge counts as 2 long before; the longest new one, to (1, 0, 0), is sqrt(101).
  EXPECT_NEAR(edge_stretch(pulled, first, first, faces, 2.0)(1), std::sqrt(101.0) / 2.0, 1e-12);
  EXPECT_THROW(edge_stretch(first.topRows(3), first, first, faces), ArgumentError);
  EXPECT_THROW(edge_stretch(first, first, first, faces, -1.0), ArgumentError);
}

TEST(BoundingBoxDiagonal, IsTheLengthOfTheBoxDiagonal) {
  Eigen::MatrixX3d vertices(3, 3);
  vertices << 1, -2, 0.5,  //
      -1, 2, 3.5,          //
      0, 0, 1;
  EXPECT_DOUBLE_EQ(bounding_box_diagonal(vertices), std::sqrt(4.0 + 16.0 + 9.0));
  EXPECT_DOUBLE_EQ(bounding_box_diagonal(vertices.topRows(1)), 0.0);
}

TEST(BoundingBoxDiagonal, RejectsEmptyAndNonFinite) {
  EXPECT_THROW(bounding_box_diagonal(Eigen::MatrixX3d(0, 3)), ArgumentError);
  Eigen::MatrixX3d vertices = corner_tetrahedron();
  vertices(2, 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    bounding_box_diagonal(vertices);
    FAIL() << "no exception";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("vertex 2"), std::string::npos) << error.what();
  }
}

TEST(FaceNormals, PointOutOfTheTetrahedron) {
  const Eigen::MatrixX3d normals = face_normals(corner_tetrahedron(), outward_tetrahedron_faces());
  Eigen::MatrixX3d expected(4, 3);
  const double third = 1.0 / std::sqrt(3.0);
  expected << 0, 0, -1, 0, -1, 0, -1, 0, 0, third, third, third;
  EXPECT_TRUE(matrices_near(normals, expected, 1e-15, 0.0));
}

TEST(FaceNormals, DegenerateFaceGetsZero) {
  Eigen::MatrixX3d vertices(3, 3);
  vertices << 0, 0, 0, 1, 1, 1, 2, 2, 2;
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, 1, 2;
  EXPECT_TRUE(face_normals(vertices, faces).isZero(0.0));
  EXPECT_EQ(face_areas(vertices, faces)(0), 0.0);
}

TEST(FaceAreas, MatchTheTetrahedron) {
  const Eigen::VectorXd areas = face_areas(corner_tetrahedron(), outward_tetrahedron_faces());
  Eigen::VectorXd expected(4);
  expected << 0.5, 0.5, 0.5, std::sqrt(3.0) / 2.0;
  EXPECT_TRUE(matrices_near(areas, expected, 1e-15, 0.0));
}

TEST(FaceAreas, RejectBadIndex) {
  Eigen::MatrixX3i faces = outward_tetrahedron_faces();
  faces(3, 0) = 4;
  EXPECT_THROW(face_areas(corner_tetrahedron(), faces), ArgumentError);
  EXPECT_THROW(face_normals(corner_tetrahedron(), faces), ArgumentError);
  EXPECT_THROW(vertex_normals(corner_tetrahedron(), faces), ArgumentError);
}

// At the corner on the axes the three faces there have equal areas, so its normal points along
// -(1, 1, 1); a vertex no face uses gets a zero row.
TEST(VertexNormals, AreTheAreaWeightedFaceNormals) {
  Eigen::MatrixX3d vertices(5, 3);
  vertices.topRows(4) = corner_tetrahedron();
  vertices.row(4) << 5.0, 5.0, 5.0;
  const Eigen::MatrixX3d normals = vertex_normals(vertices, outward_tetrahedron_faces());
  EXPECT_TRUE(normals.row(0).isApprox(-Eigen::RowVector3d::Ones() / std::sqrt(3.0), 1e-12));
  for (Eigen::Index v = 0; v < 4; ++v) EXPECT_NEAR(normals.row(v).norm(), 1.0, 1e-12);
  // The corner at (1, 0, 0): the hypotenuse face's normal weighs in with its larger area.
  const Eigen::RowVector3d expected =
      (0.5 * Eigen::RowVector3d(0, -1, 0) + 0.5 * Eigen::RowVector3d(0, 0, -1) +
       std::sqrt(3.0) / 2.0 * Eigen::RowVector3d::Ones() / std::sqrt(3.0)).normalized();
  EXPECT_TRUE(normals.row(1).isApprox(expected, 1e-12));
  EXPECT_TRUE(normals.row(4).isZero(0.0));
}

}  // namespace
}  // namespace posekit
