#include <gtest/gtest.h>

#include <posekit/correct.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/demo_shape.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/self_intersections.hpp>

#include "bent_arm.hpp"
#include "two_spheres.hpp"

#include <limits>

namespace posekit {
namespace {

class CorrectPose : public ::testing::Test {
 protected:
  const PoseSet* arm_ = &testing::bent_arm(48, 135.0);
  std::unique_ptr<Device> device_ = make_cpu_device();
};

int exactly_at(const Eigen::MatrixX3d& pose, const Eigen::MatrixX3d& target) {
  int exact = 0;
  for (Eigen::Index v = 0; v < pose.rows(); ++v) exact += pose.row(v) == target.row(v) ? 1 : 0;
  return exact;
}

TEST_F(CorrectPose, DemoArmLosesItsNewIntersections) {
  ASSERT_GT(self_intersecting_faces(arm_->pose(1), arm_->faces()).size(), 0u);
  CorrectionReport report;
  const Eigen::MatrixX3d corrected = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, {}, &report);
  ASSERT_EQ(corrected.rows(), arm_->pose(0).rows());
  EXPECT_EQ(report.result.new_intersecting_faces, 0);
  EXPECT_EQ(new_intersecting_faces(self_intersecting_faces(corrected, arm_->faces()),
                                   self_intersecting_faces(arm_->pose(0), arm_->faces()))
                .size(),
            0u);
  EXPECT_TRUE(report.field.converged());
  ASSERT_FALSE(report.field.regions.empty());
  for (const FieldRegionReport& region : report.field.regions) EXPECT_EQ(region.integration.failures, 0);
  EXPECT_GT(report.field.excluded_vertices, 0);
  // Away from the joint the result is the target itself.
  EXPECT_EQ(report.result.median_distance_to_target, 0.0);
  EXPECT_EQ(report.result.changed_vertices, static_cast<int>(corrected.rows()) - exactly_at(corrected, arm_->pose(1)));
  EXPECT_GT(report.result.changed_vertices, 0);
}

// The field is fitted only around the joint: its region is a small part of the arm, every vertex
// beyond it is the target exactly, and the whole-mesh method, fitted to every vertex, also frees
// the pose.
TEST_F(CorrectPose, RegionOfInterestAgainstTheWholeMesh) {
  CorrectionReport region;
  const Eigen::MatrixX3d local = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, {}, &region);
  CorrectionOptions options;
  options.whole_mesh = true;
  CorrectionReport whole;
  const Eigen::MatrixX3d global = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &whole);
  EXPECT_FALSE(region.field.whole_mesh);
  EXPECT_TRUE(whole.field.whole_mesh);
  ASSERT_EQ(whole.field.regions.size(), 1u);
  EXPECT_EQ(whole.field.region_vertices, arm_->vertex_count());
  EXPECT_LT(region.field.region_vertices, arm_->vertex_count() / 2);
  EXPECT_LT(region.field.constraints(), whole.field.constraints() / 2);
  EXPECT_EQ(region.result.new_intersecting_faces, 0);
  EXPECT_EQ(whole.result.new_intersecting_faces, 0);
  EXPECT_GE(exactly_at(local, arm_->pose(1)), arm_->vertex_count() - region.field.region_vertices);
  EXPECT_TRUE(whole.field.converged());
  EXPECT_LT(whole.result.median_distance_to_target, 1e-3 * whole.result.bounding_box_diagonal);
  EXPECT_GT((global - local).rowwise().norm().maxCoeff(), 0.0);
}

// Eigen sizes its products' blocks from the caches it detects, and the block depth decides how the
// fit's sums round; a correction fixes the sizes while it runs, so it gives the same bits whatever
// the processor (or the host) had set, and gives the host's sizes back.
TEST_F(CorrectPose, ResultDoesNotDependOnTheProcessorsCaches) {
  const std::ptrdiff_t l1 = Eigen::l1CacheSize(), l2 = Eigen::l2CacheSize(), l3 = Eigen::l3CacheSize();
  Eigen::setCpuCacheSizes(16 * 1024, 128 * 1024, 1024 * 1024);
  CorrectionReport small_report;
  const Eigen::MatrixX3d small = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, {}, &small_report);
  EXPECT_EQ(Eigen::l1CacheSize(), 16 * 1024);
  EXPECT_EQ(Eigen::l2CacheSize(), 128 * 1024);
  EXPECT_EQ(Eigen::l3CacheSize(), 1024 * 1024);
  Eigen::setCpuCacheSizes(96 * 1024, 4096 * 1024, 64 * 1024 * 1024);
  const Eigen::MatrixX3d large = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, {});
  EXPECT_EQ(Eigen::l1CacheSize(), 96 * 1024);
  Eigen::setCpuCacheSizes(l1, l2, l3);
  // Deep enough products that the blocks differ: a depth of 200 with a 16 KiB L1.
  ASSERT_GT(small_report.field.centers(), 400);
  EXPECT_TRUE(small == large);
}

// Two arms bent at once in one mesh: each joint is its own region, fitted on its own.
TEST_F(CorrectPose, RegionsThatDoNotInteractGetAFieldEach) {
  const Eigen::Index n = arm_->pose(0).rows();
  const Eigen::RowVector3d offset(0.0, 0.0, 3.0);
  Eigen::MatrixX3d rest(2 * n, 3);
  Eigen::MatrixX3d bent(2 * n, 3);
  rest << arm_->pose(0), arm_->pose(0).rowwise() + offset;
  bent << arm_->pose(1), arm_->pose(1).rowwise() + offset;
  Eigen::MatrixX3i faces(2 * arm_->faces().rows(), 3);
  faces << arm_->faces(), arm_->faces().array() + static_cast<int>(n);
  CorrectionReport report;
  correct_pose(rest, bent, faces, *device_, {}, &report);
  ASSERT_EQ(report.field.regions.size(), 2u);
  EXPECT_EQ(report.field.regions[0].vertices, report.field.regions[1].vertices);
  EXPECT_EQ(report.result.new_intersecting_faces, 0);
}

TEST_F(CorrectPose, ReproductionGivesTheTargetAwayFromTheCorrectedJoint) {
  CorrectionOptions options;
  options.error_factor = 1e-3;
  options.whole_mesh = true;
  options.reproduction_rings = -1;
  CorrectionReport integrated;
  const Eigen::MatrixX3d plain = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &integrated);
  options.reproduction_rings = 3;
  CorrectionReport reproduced;
  const Eigen::MatrixX3d result = correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &reproduced);
  EXPECT_EQ(integrated.field.reproduced_vertices, 0);
  EXPECT_EQ(integrated.stage("final-reproduction")->skipped, "disabled");
  ASSERT_GT(reproduced.field.reproduced_vertices, arm_->vertex_count() / 2);
  EXPECT_FALSE(reproduced.field.reproduction_skipped);
  EXPECT_GE(exactly_at(result, arm_->pose(1)), reproduced.field.reproduced_vertices);
  EXPECT_EQ(reproduced.result.new_intersecting_faces, 0);
  EXPECT_LT(reproduced.result.median_distance_to_target, integrated.result.median_distance_to_target);
  EXPECT_GT(reproduced.result.near_intersection_vertices, 0);
  EXPECT_GT(reproduced.result.median_distance_near_intersections, reproduced.result.median_distance_to_target);
  // The corrected joint itself is the integrated one.
  EXPECT_GT((result - plain).rowwise().norm().maxCoeff(), 0.0);
  EXPECT_GT((result - arm_->pose(1)).rowwise().norm().maxCoeff(), 1e-3 * reproduced.result.bounding_box_diagonal);
}

TEST_F(CorrectPose, ExclusionWindowKeepsTrajectoriesOutsideTheIntersections) {
  CorrectionOptions options;
  options.error_factor = 1e-3;
  CorrectionReport whole;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &whole);
  options.exclusion_window = 1.0;
  CorrectionReport windowed;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &windowed);
  EXPECT_GT(windowed.field.constraints(), whole.field.constraints());
  EXPECT_EQ(windowed.result.new_intersecting_faces, 0);
  EXPECT_TRUE(windowed.field.converged());
}

// Nothing intersects on the way to a gentle bend: no region, no field, the target itself.
TEST_F(CorrectPose, CleanTargetIsReproduced) {
  DemoArmOptions options;
  options.bend_angles_degrees = {45.0};
  const PoseSet gentle = make_demo_arm(options);
  CorrectionReport report;
  const Eigen::MatrixX3d corrected = correct_pose(gentle.pose(0), gentle.pose(1), gentle.faces(), *device_, {}, &report);
  EXPECT_EQ(report.field.excluded_vertices, 0);
  EXPECT_TRUE(report.field.regions.empty());
  EXPECT_EQ(report.result.intersecting_faces, 0);
  EXPECT_EQ(corrected, gentle.pose(1));
}

TEST_F(CorrectPose, RejectsBadInput) {
  const Eigen::MatrixX3d fewer = arm_->pose(1).topRows(100);
  EXPECT_THROW(correct_pose(arm_->pose(0), fewer, arm_->faces(), *device_), ArgumentError);
  Eigen::MatrixX3d with_nan = arm_->pose(0);
  with_nan(7, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(correct_pose(with_nan, arm_->pose(1), arm_->faces(), *device_), ArgumentError);
  const auto rejects = [&](const auto& change) {
    CorrectionOptions options;
    change(options);
    EXPECT_THROW(correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options), ArgumentError);
  };
  rejects([](CorrectionOptions& o) { o.key_frames = 1; });
  rejects([](CorrectionOptions& o) { o.exclusion_rings = -1; });
  rejects([](CorrectionOptions& o) { o.intersection_substeps = 0; });
  rejects([&](CorrectionOptions& o) { o.excluded_vertices = {static_cast<int>(arm_->vertex_count())}; });
  rejects([](CorrectionOptions& o) { o.error_factor = 0.0; });
  rejects([](CorrectionOptions& o) { o.time_scale = -0.5; });
  rejects([](CorrectionOptions& o) { o.time_scale = std::numeric_limits<double>::infinity(); });
  rejects([](CorrectionOptions& o) { o.blend_rings = -1; });
  rejects([](CorrectionOptions& o) { o.exclusion_window = std::numeric_limits<double>::quiet_NaN(); });
  rejects([](CorrectionOptions& o) { o.drift_passes = -1; });
  rejects([](CorrectionOptions& o) { o.separation_tolerance = 0.0; });
  rejects([](CorrectionOptions& o) { o.collar_rings = 0; });
  rejects([](CorrectionOptions& o) { o.disabled_stages = {"no-such-stage"}; });
  rejects([](CorrectionOptions& o) { o.disabled_stages = {"field"}; });
}

// The separation of the target's contacts runs only where the field's result misses the tolerance
// (or keeps new faces), and replaces it only when it is better. Pressed deep into each other, two
// spheres come out of the field clean but off the target over much of their surface; their
// separation leaves faces intersecting, so the field's result stays.
TEST(CorrectPoseContactSeparation, RunsWhereTheResultStraysAndKeepsTheBetter) {
  const Mesh apart = testing::two_spheres(3.0);
  const Mesh pressed = testing::two_spheres(0.8);
  const std::unique_ptr<Device> device = make_cpu_device();
  CorrectionReport by_default;
  correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, {}, &by_default);
  EXPECT_EQ(by_default.result.new_intersecting_faces, 0);
  ASSERT_GT(by_default.result.median_distance_to_target, 0.0);
  ASSERT_LT(by_default.result.median_distance_to_target, 1e-3 * by_default.result.bounding_box_diagonal);
  EXPECT_FALSE(by_default.stage("contact-separation")->ran);
  EXPECT_EQ(by_default.stage("contact-separation")->skipped, "nothing to repair");

  CorrectionOptions options;
  options.separation_tolerance = 1e-6;
  CorrectionReport strict;
  const Eigen::MatrixX3d result = correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, options, &strict);
  const StageReport* separation = strict.stage("contact-separation");
  EXPECT_TRUE(separation->ran);
  EXPECT_FALSE(separation->kept);
  EXPECT_TRUE(separation->note.empty());
  ASSERT_EQ(separation->details.size(), 2u);
  EXPECT_EQ(separation->details[0].first, "rounds");
  EXPECT_GT(separation->details[0].second, 0);
  EXPECT_GT(separation->details[1].second, 0);  // new faces the separation left
  EXPECT_EQ(strict.result.new_intersecting_faces, 0);
  EXPECT_TRUE(self_intersecting_faces(result, apart.faces).empty());
  EXPECT_EQ(strict.result.median_distance_to_target, by_default.result.median_distance_to_target);

  options.disabled_stages = {"contact-separation"};
  CorrectionReport without;
  correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, options, &without);
  EXPECT_EQ(without.stage("contact-separation")->skipped, "disabled");
  options.disabled_stages.clear();
  options.reproduction_rings = -1;
  CorrectionReport integrated;
  correct_pose(apart.vertices, pressed.vertices, apart.faces, *device, options, &integrated);
  EXPECT_EQ(integrated.stage("contact-separation")->skipped, "disabled");
}

TEST_F(CorrectPose, DriftCompensationBringsConstrainedVerticesCloserToTheTarget) {
  CorrectionOptions options;
  options.error_factor = 1e-3;  // a coarse field drifts more and fits faster
  options.drift_passes = 0;
  CorrectionReport plain;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &plain);
  ASSERT_EQ(plain.field.regions.size(), 1u);
  EXPECT_EQ(plain.field.regions[0].drift.after.median, plain.field.regions[0].drift.before.median);
  options.drift_passes = 1;
  CorrectionReport compensated;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &compensated);
  ASSERT_EQ(compensated.field.regions.size(), 1u);
  const FieldRegionReport& region = compensated.field.regions[0];
  EXPECT_EQ(region.fit.centers, plain.field.regions[0].fit.centers);
  EXPECT_DOUBLE_EQ(region.drift.before.median, plain.field.regions[0].drift.before.median);
  EXPECT_LT(region.drift.after.median, 0.8 * plain.field.regions[0].drift.after.median);
  EXPECT_EQ(compensated.result.new_intersecting_faces, 0);
  // A second pass starts from the first pass's ends of the vertices it measures alone.
  options.drift_passes = 2;
  CorrectionReport twice;
  correct_pose(arm_->pose(0), arm_->pose(1), arm_->faces(), *device_, options, &twice);
  ASSERT_EQ(twice.field.regions.size(), 1u);
  EXPECT_DOUBLE_EQ(twice.field.regions[0].drift.before.median, region.drift.before.median);
  EXPECT_LT(twice.field.regions[0].drift.after.median, 0.8 * plain.field.regions[0].drift.after.median);
  EXPECT_EQ(twice.result.new_intersecting_faces, 0);
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
  ASSERT_FALSE(compressed.field.regions.empty());
  EXPECT_EQ(compressed.field.regions[0].time_scale, 0.1);
  EXPECT_NE(compressed.field.centers(), equal_weights.field.centers());
  for (const CorrectionReport* report : {&equal_weights, &compressed}) {
    EXPECT_TRUE(report->field.converged());
    EXPECT_EQ(report->result.new_intersecting_faces, 0);
    EXPECT_LT(report->result.median_distance_to_target, 1e-2 * report->result.bounding_box_diagonal);
  }
}

}  // namespace
}  // namespace posekit
