// farthest_point_samples: well-spread vertices, for constraints and features.
#include <gtest/gtest.h>

#include "posekit/error.hpp"
#include "posekit/geometry.hpp"

namespace posekit {
namespace {

// Points on a line at 0, 1, 2, ..., 10, and one far off at 100.
Eigen::MatrixX3d line_and_outlier() {
  Eigen::MatrixX3d points = Eigen::MatrixX3d::Zero(12, 3);
  for (int i = 0; i <= 10; ++i) points(i, 0) = i;
  points(11, 0) = 100;
  return points;
}

TEST(FarthestPointSamples, StartsFarthestFromTheCentroidThenSpreads) {
  // 100 is farthest from the centroid, then 0 from it, then 10 (10 from 0), then 5 (5 from 0 and 10).
  EXPECT_EQ(farthest_point_samples(line_and_outlier(), 4), (std::vector<int>{11, 0, 10, 5}));
}

TEST(FarthestPointSamples, ContinuesFromSeedsAndStopsAtTheVertexCount) {
  EXPECT_EQ(farthest_point_samples(line_and_outlier(), 3, {10}), (std::vector<int>{10, 11, 0}));
  EXPECT_EQ(farthest_point_samples(line_and_outlier(), 50).size(), 12u);
  EXPECT_TRUE(farthest_point_samples(line_and_outlier(), 0).empty());
  EXPECT_THROW(farthest_point_samples(line_and_outlier(), 2, {12}), ArgumentError);
}

}  // namespace
}  // namespace posekit
