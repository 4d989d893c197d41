#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace posekit {
namespace {

using ::posekit::testing::matrices_near;

Eigen::MatrixX3d random_points(int count, unsigned seed, double spread, const Eigen::RowVector3d& offset) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(-spread, spread);
  Eigen::MatrixX3d points(count, 3);
  for (int i = 0; i < count; ++i) points.row(i) << uniform(generator), 0.5 * uniform(generator), 2.0 * uniform(generator);
  return points.rowwise() + offset;
}

double largest_norm(const Eigen::MatrixX3d& points) { return points.rowwise().norm().maxCoeff(); }

TEST(UnitSphereNormalization, PutsThePoseInTheUnitBall) {
  const Eigen::MatrixX3d pose = random_points(257, 7, 30.0, Eigen::RowVector3d(100.0, -40.0, 5.0));
  const UnitSphereNormalization normalization = unit_sphere_normalization(pose);
  const Eigen::MatrixX3d normalized = normalization.apply(pose);
  EXPECT_NEAR(largest_norm(normalized), 1.0, 1e-14);
  // The center is the bounding-box center, so the normalized box is centred on the origin.
  const Eigen::RowVector3d box_center = 0.5 * (normalized.colwise().minCoeff() + normalized.colwise().maxCoeff());
  EXPECT_LT(box_center.norm(), 1e-14);
  EXPECT_NEAR(normalization.apply_to_length(bounding_box_diagonal(pose)), bounding_box_diagonal(normalized), 1e-13);
}

TEST(UnitSphereNormalization, UndoRestoresThePose) {
  const Eigen::MatrixX3d pose = random_points(100, 11, 3.0, Eigen::RowVector3d(-7.0, 2.0, 1e3));
  const UnitSphereNormalization normalization = unit_sphere_normalization(pose);
  EXPECT_TRUE(matrices_near(normalization.undo(normalization.apply(pose)), pose, 1e-12, 1e-14));
  EXPECT_GT(normalization.scale, 0.0);
}

TEST(UnitSphereNormalization, SharedTransformCoversEveryPose) {
  const Eigen::MatrixX3d reference = random_points(50, 3, 1.0, Eigen::RowVector3d(0.0, 0.0, 0.0));
  const Eigen::MatrixX3d target = random_points(50, 5, 1.0, Eigen::RowVector3d(4.0, 1.0, 0.0));
  const UnitSphereNormalization shared = shared_unit_sphere_normalization({reference, target});
  const double reference_radius = largest_norm(shared.apply(reference));
  const double target_radius = largest_norm(shared.apply(target));
  EXPECT_LE(reference_radius, 1.0 + 1e-14);
  EXPECT_LE(target_radius, 1.0 + 1e-14);
  EXPECT_NEAR(std::max(reference_radius, target_radius), 1.0, 1e-14);

  // The same as normalizing both poses stacked into one point set.
  Eigen::MatrixX3d stacked(100, 3);
  stacked << reference, target;
  const UnitSphereNormalization whole = unit_sphere_normalization(stacked);
  EXPECT_TRUE(matrices_near(shared.center, whole.center, 0.0, 0.0));
  EXPECT_EQ(shared.scale, whole.scale);

  // The relative placement of the poses is kept: the offset between them only scales.
  const Eigen::RowVector3d offset = target.row(0) - reference.row(0);
  const Eigen::RowVector3d normalized_offset = shared.apply(target).row(0) - shared.apply(reference).row(0);
  EXPECT_TRUE(matrices_near(normalized_offset, offset * shared.scale, 1e-14, 1e-12));
}

TEST(UnitSphereNormalization, PoseSetOverloadUsesEveryPose) {
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, 1, 2;
  PoseSet poses(faces);
  Eigen::MatrixX3d first(3, 3);
  first << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Eigen::MatrixX3d second = first;
  second.col(2).setConstant(6.0);
  poses.add_pose(first, "first");
  poses.add_pose(second, "second");
  const UnitSphereNormalization normalization = shared_unit_sphere_normalization(poses);
  EXPECT_TRUE(matrices_near(normalization.center, Eigen::RowVector3d(0.5, 0.5, 3.0), 1e-15, 0.0));
  EXPECT_NEAR(normalization.scale, 1.0 / std::sqrt(0.25 + 0.25 + 9.0), 1e-15);
}

TEST(UnitSphereNormalization, RejectsDegenerateInput) {
  EXPECT_THROW(unit_sphere_normalization(Eigen::MatrixX3d(0, 3)), ArgumentError);
  EXPECT_THROW(shared_unit_sphere_normalization(std::vector<Eigen::Ref<const Eigen::MatrixX3d>>{}),
               ArgumentError);
  EXPECT_THROW(unit_sphere_normalization(Eigen::MatrixX3d::Constant(4, 3, 2.5)), ArgumentError);
  Eigen::MatrixX3d with_infinity = Eigen::MatrixX3d::Identity(3, 3);
  with_infinity(1, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(unit_sphere_normalization(with_infinity), ArgumentError);
}

}  // namespace
}  // namespace posekit
