#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/topology.hpp>

#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace posekit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Two triangles on the edge a = (0,0,0), b = (1,0,0): the first lies in the z = 0 plane with normal +z,
// the second is turned down about the edge by `fold` radians (up when negative).
struct FoldedPair {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
};

FoldedPair folded_pair(double fold, bool consistent) {
  FoldedPair pair;
  pair.vertices.resize(4, 3);
  pair.vertices << 0, 0, 0,  //
      1, 0, 0,               //
      0.3, 1, 0,             //
      0.6, -std::cos(fold), -std::sin(fold);
  pair.faces.resize(2, 3);
  if (consistent) {
    pair.faces << 0, 1, 2, 1, 0, 3;
  } else {
    pair.faces << 0, 1, 2, 0, 1, 3;
  }
  return pair;
}

double shared_edge_angle(const FoldedPair& pair) {
  const EdgeMap map = edge_map(pair.faces);
  const Eigen::VectorXd angles = dihedral_angles(pair.vertices, pair.faces);
  EXPECT_EQ(angles.size(), 5);
  // Edge 0-1 is the first in lexicographic order; the other four are boundary edges.
  EXPECT_EQ(map.edges(0, 0), 0);
  EXPECT_EQ(map.edges(0, 1), 1);
  for (int e = 1; e < 5; ++e) EXPECT_TRUE(std::isnan(angles(e))) << "boundary edge " << e;
  return angles(0);
}

TEST(DihedralAngles, FoldedPairGivesTheFoldAngle) {
  for (const double fold : {0.0, 0.7, 1.5, 2.5, 3.1, -0.4, -1.2, -2.9}) {
    EXPECT_NEAR(shared_edge_angle(folded_pair(fold, true)), fold, 1e-12) << "fold " << fold;
  }
}

TEST(DihedralAngles, InconsistentOrientationFollowsTheFirstFace) {
  for (const double fold : {0.7, -1.2}) {
    EXPECT_NEAR(shared_edge_angle(folded_pair(fold, false)), fold, 1e-12) << "fold " << fold;
  }
}

TEST(DihedralAngles, RegularTetrahedronIsConvex) {
  Eigen::MatrixX3d vertices(4, 3);
  vertices << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  Eigen::MatrixX3i faces(4, 3);
  // Wound outwards: (b - a) x (c - a) points away from the centroid at the origin.
  faces << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  const Eigen::VectorXd angles = dihedral_angles(vertices, faces);
  ASSERT_EQ(angles.size(), 6);
  const double expected = kPi - std::acos(1.0 / 3.0);  // between the normals: pi minus the interior angle
  for (int e = 0; e < 6; ++e) EXPECT_NEAR(angles(e), expected, 1e-12) << "edge " << e;

  // Turned inside out, every edge is concave.
  Eigen::MatrixX3i inward = faces;
  inward.col(1).swap(inward.col(2));
  const Eigen::VectorXd inverted = dihedral_angles(vertices, inward);
  for (int e = 0; e < 6; ++e) EXPECT_NEAR(inverted(e), -expected, 1e-12) << "edge " << e;
}

TEST(DihedralAngles, NonManifoldEdgeGivesNaN) {
  Eigen::MatrixX3d vertices(5, 3);
  vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  Eigen::MatrixX3i faces(3, 3);
  faces << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const Eigen::VectorXd angles = dihedral_angles(vertices, faces);
  EXPECT_TRUE(std::isnan(angles(0)));  // edge 0-1 has three faces
}

TEST(DihedralAngles, RejectsMismatchedTopology) {
  const FoldedPair pair = folded_pair(0.5, true);
  const EdgeMap map = edge_map(pair.faces);
  const AdjacencyLists around = edge_faces(map);
  Eigen::MatrixX3i more_faces(3, 3);
  more_faces << 0, 1, 2, 1, 0, 3, 1, 2, 3;
  EXPECT_THROW(dihedral_angles(pair.vertices, more_faces, map, around), ArgumentError);
  EXPECT_THROW(dihedral_angles(pair.vertices, pair.faces, map, AdjacencyLists()), ArgumentError);
  EXPECT_THROW(dihedral_angles(pair.vertices.topRows(3), pair.faces), ArgumentError);
}

// Rigid motions leave dihedral angles unchanged; on a real pose with shared topology the two
// overloads agree.
TEST(DihedralAngles, InvariantUnderRigidMotionOnRealPose) {
  POSEKIT_REQUIRE_SHARED_POSE(file, "lion-poses/lion-01.obj");
  const Mesh mesh = read_mesh(file);
  const EdgeMap map = edge_map(mesh.faces);
  const AdjacencyLists around = edge_faces(map);
  const Eigen::VectorXd angles = dihedral_angles(mesh.vertices, mesh.faces, map, around);
  ASSERT_EQ(angles.size(), map.edges.rows());
  EXPECT_TRUE(angles.allFinite());  // the lion is closed and manifold
  EXPECT_LE(angles.cwiseAbs().maxCoeff(), kPi);

  Eigen::Matrix3d rotation;
  rotation = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, 2, -0.5).normalized());
  const Eigen::MatrixX3d moved =
      (mesh.vertices * rotation.transpose()).rowwise() + Eigen::RowVector3d(3.0, -1.0, 0.25);
  const Eigen::VectorXd moved_angles = dihedral_angles(moved, mesh.faces);
  EXPECT_TRUE(::posekit::testing::matrices_near(moved_angles, angles, 1e-7, 0.0));
}

}  // namespace
}  // namespace posekit
