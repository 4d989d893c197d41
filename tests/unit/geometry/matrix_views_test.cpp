// The per-pose functions take Eigen::Ref views: matrices with a dynamic column count (as libigl
// keeps them) and strided views into larger matrices give exactly what MatrixX3d / MatrixX3i give.
#include <posekit/geometry.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/winding_numbers.hpp>

#include "bent_arm.hpp"

#include <gtest/gtest.h>

namespace posekit {
namespace {

// The bent arm intersects itself at the inside of its joint, so every function has work to do.
struct Views {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  Eigen::MatrixXd dynamic_vertices;
  Eigen::MatrixXi dynamic_faces;
  Eigen::MatrixXd wide_vertices;  // the vertices as columns 1-3 of every other row of a wider matrix
  Eigen::MatrixXi wide_faces;
};

Views bent_arm_views() {
  const PoseSet& arm = testing::bent_arm(16, 150.0);
  Views views;
  views.vertices = arm.pose(1);
  views.faces = arm.faces();
  views.dynamic_vertices = views.vertices;
  views.dynamic_faces = views.faces;
  views.wide_vertices = Eigen::MatrixXd::Constant(2 * views.vertices.rows(), 5, -7.0);
  views.wide_faces = Eigen::MatrixXi::Constant(2 * views.faces.rows(), 4, -1);
  for (Eigen::Index v = 0; v < views.vertices.rows(); ++v) views.wide_vertices.block<1, 3>(2 * v, 1) = views.vertices.row(v);
  for (Eigen::Index f = 0; f < views.faces.rows(); ++f) views.wide_faces.block<1, 3>(2 * f, 1) = views.faces.row(f);
  return views;
}

// Equal value for value, NaN (a boundary edge's dihedral angle) matching NaN.
bool same_values(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && (a.array() == b.array() || (a.array().isNaN() && b.array().isNaN())).all();
}

TEST(MatrixViews, DynamicColumnMatricesGiveTheSameResults) {
  const Views views = bent_arm_views();
  ASSERT_FALSE(self_intersecting_faces(views.vertices, views.faces).empty());
  EXPECT_EQ(self_intersecting_faces(views.dynamic_vertices, views.dynamic_faces),
            self_intersecting_faces(views.vertices, views.faces));
  EXPECT_EQ(face_normals(views.dynamic_vertices, views.dynamic_faces), face_normals(views.vertices, views.faces));
  EXPECT_EQ(bounding_box_diagonal(views.dynamic_vertices), bounding_box_diagonal(views.vertices));
  const Eigen::MatrixX3d points = views.vertices.topRows(20) * 0.5;
  EXPECT_EQ(winding_numbers(views.dynamic_vertices, views.dynamic_faces, points),
            winding_numbers(views.vertices, views.faces, points));
}

TEST(MatrixViews, StridedViewsGiveTheSameResults) {
  const Views views = bent_arm_views();
  // Every other row, columns 1 to 3: an outer stride and an inner stride other than the matrix's own.
  const Eigen::Index vertex_count = views.vertices.rows(), face_count = views.faces.rows();
  const Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>> strided_vertices(
      views.wide_vertices.data() + views.wide_vertices.rows(), vertex_count, 3,
      Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(views.wide_vertices.rows(), 2));
  const Eigen::Map<const Eigen::MatrixXi, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>> strided_faces(
      views.wide_faces.data() + views.wide_faces.rows(), face_count, 3,
      Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(views.wide_faces.rows(), 2));
  ASSERT_EQ(Eigen::MatrixX3d(strided_vertices), views.vertices);
  EXPECT_EQ(self_intersecting_faces(strided_vertices, strided_faces), self_intersecting_faces(views.vertices, views.faces));
  EXPECT_EQ(vertex_normals(strided_vertices, strided_faces), vertex_normals(views.vertices, views.faces));
  EXPECT_TRUE(same_values(dihedral_angles(strided_vertices, strided_faces), dihedral_angles(views.vertices, views.faces)));
}

}  // namespace
}  // namespace posekit
