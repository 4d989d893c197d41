#include "correct/vertex_classification.hpp"

#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

namespace posekit::detail {
namespace {

// Two separate triangles; in the middle frame the second one passes through the first.
struct PassingTriangles {
  Eigen::MatrixX3i faces;
  std::vector<Eigen::MatrixX3d> frames;
  std::vector<FacePairs> pairs() const {
    std::vector<FacePairs> out;
    for (const Eigen::MatrixX3d& frame : frames) out.push_back(self_intersecting_face_pairs(frame, faces));
    return out;
  }
  AdjacencyLists neighbours() const { return vertex_neighbours(faces, 6); }
};

PassingTriangles passing_triangles() {
  PassingTriangles scene;
  scene.faces.resize(2, 3);
  scene.faces << 0, 1, 2, 3, 4, 5;
  Eigen::MatrixX3d apart(6, 3);
  apart << 0, 0, 0, 1, 0, 0, 0, 1, 0,   // in the plane z = 0
      0.2, 0.2, 1, 0.2, 0.2, 2, 0.3, 0.3, 2;  // vertical, above it
  Eigen::MatrixX3d through = apart;
  through.bottomRows(3).col(2).array() -= 1.5;  // now crossing z = 0
  scene.frames = {apart, through, apart};
  return scene;
}

TEST(ClassifyVertices, FlagsEachFramesIntersectionsAndTheirTransit) {
  const PassingTriangles scene = passing_triangles();
  const VertexClassification classification = classify_vertices(scene.pairs(), scene.faces, scene.neighbours(), 0, {});
  ASSERT_EQ(classification.unconstrained_in_frame.size(), 3u);
  for (int v = 0; v < 6; ++v) {
    EXPECT_FALSE(classification.unconstrained_in_frame[0][v]) << v;
    EXPECT_TRUE(classification.unconstrained_in_frame[1][v]) << v;
    EXPECT_FALSE(classification.unconstrained_in_frame[2][v]) << v;
    EXPECT_FALSE(classification.constrained[v]) << v;
    EXPECT_TRUE(classification.in_transit[v]) << v;
    EXPECT_TRUE(classification.near_intersections[v]) << v;
  }
  EXPECT_EQ(classification.excluded, 6);
  EXPECT_TRUE(classification.reference_intersecting.empty());
  EXPECT_TRUE(classification.target_intersecting.empty());
}

TEST(ClassifyVertices, UserExclusionsHoldInEveryFrame) {
  PassingTriangles scene = passing_triangles();
  scene.frames[1] = scene.frames[0];
  const VertexClassification classification = classify_vertices(scene.pairs(), scene.faces, scene.neighbours(), 1, {4});
  for (const std::vector<char>& flags : classification.unconstrained_in_frame) {
    EXPECT_TRUE(flags[4]);
    EXPECT_FALSE(flags[0]);
  }
  EXPECT_EQ(classification.excluded, 1);
  EXPECT_TRUE(classification.near_intersections[4]);
  EXPECT_FALSE(classification.near_intersections[3]);
  EXPECT_THROW(classify_vertices(scene.pairs(), scene.faces, scene.neighbours(), 1, {6}), ArgumentError);
}

}  // namespace
}  // namespace posekit::detail
