// The tracker re-tests only what moved; every answer must equal the whole-mesh test of the same pose.
#include <posekit/error.hpp>
#include <posekit/self_intersection_tracker.hpp>
#include <posekit/self_intersections.hpp>

#include "bent_arm.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace posekit {
namespace {

class SelfIntersectionTrackerTest : public ::testing::Test {
 protected:
  const PoseSet* arm_ = &testing::bent_arm(16, 150.0);
};

TEST_F(SelfIntersectionTrackerTest, StartsWithTheWholeMeshTest) {
  const SelfIntersectionTracker tracker(arm_->pose(1), arm_->faces());
  const FacePairs whole = self_intersecting_face_pairs(arm_->pose(1), arm_->faces());
  ASSERT_FALSE(whole.empty());
  EXPECT_EQ(tracker.pairs(), whole);
  EXPECT_EQ(tracker.vertices(), arm_->pose(1));
}

// Random local moves (a vertex and its neighbours pushed by up to a few edge lengths, some far
// enough to cross other parts, some collapsing faces onto a line) probed and kept in turn.
TEST_F(SelfIntersectionTrackerTest, AgreesWithTheWholeMeshTestAfterLocalMoves) {
  const Eigen::MatrixX3i& faces = arm_->faces();
  SelfIntersectionTracker tracker(arm_->pose(1), faces);
  Eigen::MatrixX3d pose = arm_->pose(1);
  std::mt19937 random(7);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(pose.rows()) - 1);
  std::normal_distribution<double> offset(0.0, 0.15);
  int changed_answers = 0;
  for (int step = 0; step < 60; ++step) {
    Eigen::MatrixX3d candidate = tracker.vertices();
    const int center = pick(random);
    const Eigen::RowVector3d push(offset(random), offset(random), offset(random));
    for (Eigen::Index v = 0; v < candidate.rows(); ++v) {
      if ((candidate.row(v) - tracker.vertices().row(center)).norm() < 0.3) candidate.row(v) += push;
    }
    if (step % 10 == 3) {  // a face collapsed onto a line
      const int f = pick(random) % static_cast<int>(faces.rows());
      candidate.row(faces(f, 2)) = 0.5 * (candidate.row(faces(f, 0)) + candidate.row(faces(f, 1)));
    }
    if (step % 10 == 6) candidate.row(pick(random)) = candidate.row(pick(random));  // faces stretched across the arm
    if (step % 20 == 9) candidate *= 1.01;  // everything moved
    const FacePairs expected = self_intersecting_face_pairs(candidate, faces);
    const FacePairs probed = tracker.pairs_if(candidate);
    ASSERT_EQ(probed, expected) << "step " << step;
    changed_answers += probed != tracker.pairs() ? 1 : 0;
    if (step % 2 == 0) {
      tracker.update(candidate);
      ASSERT_EQ(tracker.pairs(), expected) << "step " << step;
      ASSERT_EQ(tracker.vertices(), candidate);
    }
  }
  EXPECT_GT(changed_answers, 10);  // the moves did change what intersects
}

// Faces of every size from the start (vertices pulled a little, far and across the whole arm, so
// the tracker's grid holds them at several levels), then moved back one by one and pulled again
// elsewhere: the probes and updates still agree with the whole-mesh test.
TEST_F(SelfIntersectionTrackerTest, AgreesWithTheWholeMeshTestOverFacesOfEverySize) {
  const Eigen::MatrixX3i& faces = arm_->faces();
  Eigen::MatrixX3d start = arm_->pose(1);
  std::mt19937 random(11);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(start.rows()) - 1);
  const Eigen::RowVector3d extent = start.colwise().maxCoeff() - start.colwise().minCoeff();
  std::vector<int> pulled;
  for (int k = 0; k < 12; ++k) {
    const int v = pick(random);
    const double reach = std::pow(4.0, k % 6) * 0.01;  // from a hundredth of the arm to ten times it
    start.row(v) += reach * extent.cwiseProduct(Eigen::RowVector3d(1.0, -0.5, 0.25));
    pulled.push_back(v);
  }
  SelfIntersectionTracker tracker(start, faces);
  ASSERT_EQ(tracker.pairs(), self_intersecting_face_pairs(start, faces));
  for (size_t step = 0; step < pulled.size(); ++step) {
    Eigen::MatrixX3d candidate = tracker.vertices();
    candidate.row(pulled[step]) = arm_->pose(1).row(pulled[step]);
    candidate.row(pick(random)) += 0.3 * extent;
    const FacePairs expected = self_intersecting_face_pairs(candidate, faces);
    ASSERT_EQ(tracker.pairs_if(candidate), expected) << "step " << step;
    tracker.update(candidate);
    ASSERT_EQ(tracker.pairs(), expected) << "step " << step;
  }
}

TEST_F(SelfIntersectionTrackerTest, CopiesAreIndependent) {
  SelfIntersectionTracker tracker(arm_->pose(0), arm_->faces());
  ASSERT_TRUE(tracker.pairs().empty());
  const SelfIntersectionTracker copy = tracker;
  tracker.update(arm_->pose(1));
  EXPECT_FALSE(tracker.pairs().empty());
  EXPECT_TRUE(copy.pairs().empty());
  EXPECT_EQ(copy.pairs_if(arm_->pose(1)), tracker.pairs());
}

TEST_F(SelfIntersectionTrackerTest, RejectsAPoseOfAnotherSize) {
  const SelfIntersectionTracker tracker(arm_->pose(0), arm_->faces());
  EXPECT_THROW(tracker.pairs_if(arm_->pose(0).topRows(10)), ArgumentError);
  Eigen::MatrixX3d with_nan = arm_->pose(0);
  with_nan(3, 1) = std::nan("");
  EXPECT_THROW(tracker.pairs_if(with_nan), ArgumentError);
}

}  // namespace
}  // namespace posekit
