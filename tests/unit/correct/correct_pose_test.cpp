#include <gtest/gtest.h>

#include <posekit/correct.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/demo_shape.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/self_intersections.hpp>

#include "two_spheres.hpp"

#include <limits>


namespace posekit {
namespace {

class CorrectPose : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    DemoArmOptions options;
    options.bend_angles_degrees = {135.0};
    arm_ = new PoseSet(make_demo_arm(options));
  }
  static void TearDownTestSuite() {
    delete arm_;
    arm_ = nullptr;
  }
  static PoseSet* arm_;
  std::unique_ptr<Device> device_ = make_cpu_device();
};
PoseSet* CorrectPose::arm_ = nullptr;

TEST_F(CorrectPose, DemoArmLosesItsNewIntersections) {
  ASSERT_GT(self_intersecting_faces(arm_->pose(1), arm_->faces()).size(), 0u);
  CorrectionReport report;
  const Eigen::MatrixX3d corrected = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, {}, &report);
  ASSERT_EQ(corrected.rows(), arm_->pose(0).rows());
  EXPECT_EQ(report.new_intersecting_faces, 0);
  EXPECT_EQ(new_intersecting_faces(self_intersecting_faces(corrected, arm_->faces()),
                                   self_intersecting_faces(arm_->pose(0), arm_->faces()))
                .size(),
            0u);
  EXPECT_TRUE(report.fit.converged);
  EXPECT_EQ(report.integration.failures, 0);
  EXPECT_GT(report.excluded_vertices, 0);
  // Away from the joint the target is reproduced, within the accuracy the default error bound gives.
  EXPECT_LT(report.median_distance_to_target, 1e-2 * report.bounding_box_diagonal);
}

TEST_F(CorrectPose, ReproductionGivesTheTargetAwayFromTheCorrectedJoint) {
  CorrectionOptions options;
  options.error_factor = 1e-3;
  options.reproduction_rings = -1;
  CorrectionReport integrated;
  const Eigen::MatrixX3d plain = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &integrated);
  options.reproduction_rings = 3;
  CorrectionReport reproduced;
  const Eigen::MatrixX3d result = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &reproduced);
  EXPECT_EQ(integrated.reproduced_vertices, 0);
  ASSERT_GT(reproduced.reproduced_vertices, arm_->vertex_count() / 2);
  EXPECT_FALSE(reproduced.reproduction_skipped);
  int exact = 0;
  for (Eigen::Index v = 0; v < result.rows(); ++v) exact += result.row(v) == arm_->pose(1).row(v) ? 1 : 0;
  EXPECT_GE(exact, reproduced.reproduced_vertices);
  // The final reproduction keeps the result only around the target's own intersections, so it
  // gives back at least as much of the target.
  EXPECT_EQ(integrated.final_reproduced_vertices, 0);
  EXPECT_GE(reproduced.final_reproduced_vertices, reproduced.reproduced_vertices);
  EXPECT_GE(exact, reproduced.final_reproduced_vertices);
  EXPECT_EQ(reproduced.new_intersecting_faces, 0);
  EXPECT_LT(reproduced.median_distance_to_target, integrated.median_distance_to_target);
  EXPECT_GT(reproduced.near_intersection_vertices, 0);
  EXPECT_GT(reproduced.median_distance_near_intersections, reproduced.median_distance_to_target);
  // The corrected joint itself is the integrated one.
  EXPECT_GT((result - plain).rowwise().norm().maxCoeff(), 0.0);
  EXPECT_GT((result - arm_->pose(1)).rowwise().norm().maxCoeff(), 1e-3 * reproduced.bounding_box_diagonal);
}

TEST_F(CorrectPose, ExclusionWindowKeepsTrajectoriesOutsideTheIntersections) {
  CorrectionOptions options;
  options.error_factor = 1e-3;
  CorrectionReport whole;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &whole);
  options.exclusion_window = 1.0;
  CorrectionReport windowed;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &windowed);
  EXPECT_GT(windowed.constraints, whole.constraints);
  EXPECT_EQ(windowed.new_intersecting_faces, 0);
  EXPECT_TRUE(windowed.fit.converged);
}

TEST_F(CorrectPose, CleanTargetIsReproduced) {
  DemoArmOptions options;
  options.bend_angles_degrees = {45.0};
  const PoseSet gentle = make_demo_arm(options);
  CorrectionReport report;
  const Eigen::MatrixX3d corrected = correct_pose(gentle.pose(0), gentle.pose(1), gentle.faces(), *device_, {}, &report);
  EXPECT_EQ(report.excluded_vertices, 0);
  EXPECT_EQ(report.result_intersecting_faces, 0);
  EXPECT_LT(report.max_distance_to_target, 1e-2 * report.bounding_box_diagonal);
  EXPECT_LT(report.median_distance_to_target, 1e-3 * report.bounding_box_diagonal);
}

TEST_F(CorrectPose, RejectsBadInput) {
  const Eigen::MatrixX3d fewer = arm_->pose(1).topRows(100);
  EXPECT_THROW(correct_pose(arm_->pose(0), fewer, arm_->faces(), *device_), ArgumentError);
  Eigen::MatrixX3d with_nan = arm_->pose(0);
  with_nan(7, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(correct_pose(with_nan, arm_->pose(1), arm_->faces(), *device_), ArgumentError);
  CorrectionOptions options;
  options.key_frames = 1;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.exclusion_rings = -1;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.intersection_substeps = 0;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.excluded_vertices = {static_cast<int>(arm_->vertex_count())};
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.error_factor = 0.0;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.time_scale = -0.5;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.time_scale = std::numeric_limits<double>::infinity();
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.blend_rings = -1;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.exclusion_window = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.drift_passes = -1;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  options = {};
  options.separation_tolerance = 0.0;
  EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
}

// The separation of the target's contacts runs only where the field's result misses the tolerance
// (or keeps new faces), and replaces it only when it is better. Pressed deep into each other, two
// spheres come out of the field clean but off the target over most of their surface; their
// separation leaves faces intersecting, so the field's result stays.
TEST(CorrectPoseContactSeparation, RunsWhereTheResultStraysAndKeepsTheBetter) {
  const Mesh apart = testing::two_spheres(3.0);
  const Mesh pressed = testing::two_spheres(0.8);
  const std::unique_ptr<Device> device = make_cpu_device();
  CorrectionReport by_default;
  correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, {}, &by_default);
  EXPECT_EQ(by_default.new_intersecting_faces, 0);
  ASSERT_GT(by_default.median_distance_to_target, 0.0);
  ASSERT_LT(by_default.median_distance_to_target, 1e-3 * by_default.bounding_box_diagonal);
  EXPECT_FALSE(by_default.separation_tried);

  CorrectionOptions options;
  options.separation_tolerance = 1e-6;
  CorrectionReport strict;
  const Eigen::MatrixX3d result = correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, options, &strict);
  EXPECT_TRUE(strict.separation_tried);
  EXPECT_GT(strict.separation_rounds, 0);
  EXPECT_GT(strict.separation_new_faces, 0);
  EXPECT_FALSE(strict.separated);
  EXPECT_EQ(strict.new_intersecting_faces, 0);
  EXPECT_TRUE(self_intersecting_faces(result, apart.faces).empty());
  EXPECT_EQ(strict.median_distance_to_target, by_default.median_distance_to_target);

  options.contact_separation = false;
  CorrectionReport without;
  correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, options, &without);
  EXPECT_FALSE(without.separation_tried);
  options.contact_separation = true;
  options.reproduction_rings = -1;
  CorrectionReport integrated;
  correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, options, &integrated);
  EXPECT_FALSE(integrated.separation_tried);
}

TEST_F(CorrectPose, DriftCompensationBringsConstrainedVerticesCloserToTheTarget) {
  CorrectionOptions options;
  options.error_factor = 1e-3;  // a coarse field drifts more and fits faster
  options.drift_passes = 0;
  CorrectionReport plain;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &plain);
  EXPECT_EQ(plain.drift.after.median, plain.drift.before.median);
  options.drift_passes = 1;
  CorrectionReport compensated;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &compensated);
  EXPECT_EQ(compensated.fit.centers, plain.fit.centers);
  EXPECT_DOUBLE_EQ(compensated.drift.before.median, plain.drift.before.median);
  EXPECT_LT(compensated.drift.after.median, 0.8 * plain.drift.after.median);
  EXPECT_EQ(compensated.new_intersecting_faces, 0);
}

TEST_F(CorrectPose, TimeScaleChangesTheFieldNotTheOutcome) {
  CorrectionOptions options;
  options.error_factor = 1e-3;
  options.time_scale = 1.0;
  CorrectionReport equal_weights;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &equal_weights);
  options.time_scale = 0.1;
  CorrectionReport compressed;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &compressed);
  EXPECT_EQ(compressed.time_scale, 0.1);
  EXPECT_NE(compressed.fit.centers, equal_weights.fit.centers);
  for (const CorrectionReport* report : {&equal_weights, &compressed}) {
    EXPECT_TRUE(report->fit.converged);
    EXPECT_EQ(report->new_intersecting_faces, 0);
    EXPECT_LT(report->median_distance_to_target, 1e-2 * report->bounding_box_diagonal);
  }
}

}  // namespace
}  // namespace posekit
