#include <posekit/error.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/topology.hpp>

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace posekit {
namespace {

std::vector<int> as_vector(IndexRange range) { return {range.begin(), range.end()}; }

// Corners (0,0,0), (1,0,0), (0,1,0), (0,0,1); faces wound outwards.
Eigen::MatrixX3i tetrahedron_faces() {
  Eigen::MatrixX3i faces(4, 3);
  faces << 0, 2, 1,  //
      0, 1, 3,       //
      0, 3, 2,       //
      1, 2, 3;
  return faces;
}

TEST(EdgeMap, TetrahedronHasSixSortedEdges) {
  const EdgeMap map = edge_map(tetrahedron_faces());
  Eigen::MatrixX2i expected(6, 2);
  expected << 0, 1, 0, 2, 0, 3, 1, 2, 1, 3, 2, 3;
  EXPECT_EQ(map.edges, expected);
  Eigen::MatrixX3i expected_face_edges(4, 3);
  // Column k is the edge from corner k to corner k + 1.
  expected_face_edges << 1, 3, 0,  // 0-2, 2-1, 1-0
      0, 4, 2,                     // 0-1, 1-3, 3-0
      2, 5, 1,                     // 0-3, 3-2, 2-0
      3, 5, 4;                     // 1-2, 2-3, 3-1
  EXPECT_EQ(map.face_edges, expected_face_edges);
}

TEST(EdgeMap, FaceEdgesJoinTheRightCorners) {
  Eigen::MatrixX3i faces(3, 3);
  faces << 4, 0, 7, 7, 0, 2, 2, 9, 4;
  const EdgeMap map = edge_map(faces);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k);
      const int b = faces(f, (k + 1) % 3);
      const Eigen::Index e = map.face_edges(f, k);
      EXPECT_EQ(map.edges(e, 0), std::min(a, b));
      EXPECT_EQ(map.edges(e, 1), std::max(a, b));
    }
  }
  for (Eigen::Index e = 1; e < map.edges.rows(); ++e) {
    EXPECT_TRUE(std::make_pair(map.edges(e - 1, 0), map.edges(e - 1, 1)) <
                std::make_pair(map.edges(e, 0), map.edges(e, 1)));
  }
}

TEST(EdgeMap, RejectsNegativeIndex) {
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, -1, 2;
  EXPECT_THROW(edge_map(faces), ArgumentError);
}

TEST(EdgeMap, EmptyFaceListGivesNoEdge) {
  const EdgeMap map = edge_map(Eigen::MatrixX3i(0, 3));
  EXPECT_EQ(map.edges.rows(), 0);
  EXPECT_EQ(map.face_edges.rows(), 0);
  EXPECT_EQ(edge_faces(map).item_count(), 0);
}

TEST(EdgeFaces, TetrahedronEdgesHaveTwoFaces) {
  const EdgeMap map = edge_map(tetrahedron_faces());
  const AdjacencyLists around = edge_faces(map);
  ASSERT_EQ(around.item_count(), 6);
  EXPECT_EQ(as_vector(around[0]), (std::vector<int>{0, 1}));  // edge 0-1
  EXPECT_EQ(as_vector(around[1]), (std::vector<int>{0, 2}));  // edge 0-2
  EXPECT_EQ(as_vector(around[2]), (std::vector<int>{1, 2}));  // edge 0-3
  EXPECT_EQ(as_vector(around[3]), (std::vector<int>{0, 3}));  // edge 1-2
  EXPECT_EQ(as_vector(around[4]), (std::vector<int>{1, 3}));  // edge 1-3
  EXPECT_EQ(as_vector(around[5]), (std::vector<int>{2, 3}));  // edge 2-3
}

TEST(EdgeFaces, TwoTrianglesShareOneEdge) {
  Eigen::MatrixX3i faces(2, 3);
  faces << 0, 1, 2, 2, 1, 3;
  const EdgeMap map = edge_map(faces);
  ASSERT_EQ(map.edges.rows(), 5);
  const AdjacencyLists around = edge_faces(map);
  for (int e = 0; e < 5; ++e) {
    const bool shared = map.edges(e, 0) == 1 && map.edges(e, 1) == 2;
    EXPECT_EQ(around.count(e), shared ? 2 : 1) << "edge " << e;
  }
}

TEST(EdgeFaces, NonManifoldFanListsEveryFace) {
  Eigen::MatrixX3i faces(3, 3);
  faces << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const EdgeMap map = edge_map(faces);
  ASSERT_EQ(map.edges(0, 0), 0);
  ASSERT_EQ(map.edges(0, 1), 1);
  const AdjacencyLists around = edge_faces(map);
  EXPECT_EQ(as_vector(around[0]), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(around.indices().size(), 9u);  // 3 on the spine, 2 boundary edges per face
}

TEST(EdgeFaces, RepeatedVertexCountsTheFaceOnce) {
  Eigen::MatrixX3i faces(2, 3);
  faces << 0, 0, 1, 0, 1, 2;
  const EdgeMap map = edge_map(faces);
  // Edges: 0-0, 0-1, 0-2, 1-2.
  ASSERT_EQ(map.edges.rows(), 4);
  EXPECT_EQ(map.edges(0, 0), map.edges(0, 1));
  const AdjacencyLists around = edge_faces(map);
  EXPECT_EQ(as_vector(around[1]), (std::vector<int>{0, 1}));
}

TEST(VertexNeighbours, TetrahedronRingsHoldTheOtherThree) {
  const AdjacencyLists rings = vertex_neighbours(tetrahedron_faces(), 4);
  ASSERT_EQ(rings.item_count(), 4);
  EXPECT_EQ(as_vector(rings[0]), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(as_vector(rings[1]), (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(as_vector(rings[2]), (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(as_vector(rings[3]), (std::vector<int>{0, 1, 2}));
}

TEST(VertexNeighbours, FanAndIsolatedVertex) {
  Eigen::MatrixX3i faces(3, 3);
  faces << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const AdjacencyLists rings = vertex_neighbours(faces, 6);
  EXPECT_EQ(as_vector(rings[0]), (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(as_vector(rings[1]), (std::vector<int>{0, 2, 3, 4}));
  EXPECT_EQ(as_vector(rings[4]), (std::vector<int>{0, 1}));
  EXPECT_TRUE(rings[5].empty());  // vertex 5 is in no face
}

TEST(VertexNeighbours, NeverListsTheVertexItself) {
  Eigen::MatrixX3i faces(1, 3);
  faces << 2, 2, 0;
  const AdjacencyLists rings = vertex_neighbours(faces, 3);
  EXPECT_EQ(as_vector(rings[2]), (std::vector<int>{0}));
  EXPECT_EQ(as_vector(rings[0]), (std::vector<int>{2}));
  EXPECT_TRUE(rings[1].empty());
}

TEST(VertexNeighbours, RejectsIndexOutOfRange) {
  Eigen::MatrixX3i faces(2, 3);
  faces << 0, 1, 2, 1, 2, 3;
  try {
    vertex_neighbours(faces, 3);
    FAIL() << "no exception";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("face 1 corner 2"), std::string::npos) << error.what();
  }
}

TEST(VertexFaces, TetrahedronAndRepeatedCorner) {
  const AdjacencyLists around = vertex_faces(tetrahedron_faces(), 4);
  EXPECT_EQ(as_vector(around[0]), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(as_vector(around[1]), (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(as_vector(around[2]), (std::vector<int>{0, 2, 3}));
  EXPECT_EQ(as_vector(around[3]), (std::vector<int>{1, 2, 3}));

  Eigen::MatrixX3i faces(2, 3);
  faces << 1, 1, 0, 1, 0, 2;
  const AdjacencyLists repeated = vertex_faces(faces, 3);
  EXPECT_EQ(as_vector(repeated[1]), (std::vector<int>{0, 1}));
  EXPECT_THROW(vertex_faces(faces, 2), ArgumentError);
}

TEST(AdjacencyLists, RejectsInconsistentOffsets) {
  EXPECT_THROW(AdjacencyLists({1, 2}, {0, 0}), ArgumentError);
  EXPECT_THROW(AdjacencyLists({0, 2, 1}, {0}), ArgumentError);
  EXPECT_THROW(AdjacencyLists({0, 1}, {0, 1}), ArgumentError);
  EXPECT_THROW(AdjacencyLists({}, {}), ArgumentError);
  const AdjacencyLists lists({0, 2, 2, 3}, {4, 5, 6});
  EXPECT_EQ(lists.item_count(), 3);
  EXPECT_EQ(lists.count(1), 0);
  EXPECT_EQ(lists[2][0], 6);
}

// The elephant is a closed genus-0 surface: every edge borders two faces and V - E + F = 2.
TEST(TopologyOnRealData, ElephantIsClosedAndConsistent) {
  POSEKIT_REQUIRE_SHARED_POSE(file, "elephant-poses/elephant-01.obj");
  const Mesh mesh = read_mesh(file);
  const EdgeMap map = edge_map(mesh.faces);
  EXPECT_EQ(map.edges.rows() * 2, mesh.faces.rows() * 3);
  EXPECT_EQ(mesh.vertices.rows() - map.edges.rows() + mesh.faces.rows(), 2);
  const AdjacencyLists around = edge_faces(map);
  for (int e = 0; e < around.item_count(); ++e) ASSERT_EQ(around.count(e), 2) << "edge " << e;

  const auto vertex_count = static_cast<int>(mesh.vertices.rows());
  const AdjacencyLists rings = vertex_neighbours(mesh.faces, vertex_count);
  const AdjacencyLists stars = vertex_faces(mesh.faces, vertex_count);
  // On a closed manifold each vertex has as many neighbours as incident faces; the ring sizes sum to 2E.
  EXPECT_EQ(static_cast<Eigen::Index>(rings.indices().size()), 2 * map.edges.rows());
  for (int v = 0; v < vertex_count; ++v) ASSERT_EQ(rings.count(v), stars.count(v)) << "vertex " << v;
}

// The horse has holes: its boundary edges (one face each) close into loops, so every boundary vertex
// has exactly two boundary edges.
TEST(TopologyOnRealData, HorseBoundaryFormsLoops) {
  POSEKIT_REQUIRE_SHARED_POSE(file, "horse-poses/horse-10.obj");
  const Mesh mesh = read_mesh(file);
  const EdgeMap map = edge_map(mesh.faces);
  const AdjacencyLists around = edge_faces(map);
  std::vector<int> boundary_degree(static_cast<size_t>(mesh.vertices.rows()), 0);
  int boundary_edges = 0;
  for (int e = 0; e < around.item_count(); ++e) {
    ASSERT_LE(around.count(e), 2);
    if (around.count(e) == 1) {
      ++boundary_edges;
      ++boundary_degree[static_cast<size_t>(map.edges(e, 0))];
      ++boundary_degree[static_cast<size_t>(map.edges(e, 1))];
    }
  }
  EXPECT_GT(boundary_edges, 0);
  for (const int degree : boundary_degree) EXPECT_TRUE(degree == 0 || degree == 2);
}

}  // namespace
}  // namespace posekit
