// The sequence: every frame free, the corrections blended in time (smoother than frame by frame),
// frames far from any contact untouched, earlier corrections reused, bad input refused.
#include <posekit/correct_sequence.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/demo_shape.hpp>
#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

#include <memory>

namespace posekit::testing {
namespace {

// The arm bending in and out through itself: bends of 70 degrees and more intersect.
class ArmSequence : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    DemoArmOptions options;
    options.bend_angles_degrees = {0, 10, 20, 30, 45, 55, 60, 65, 70, 75, 80, 75, 70, 65, 60, 55, 45, 30, 20, 10, 0};
    arm_ = std::make_unique<PoseSet>(make_demo_arm(options));
    for (int k = 1; k < arm_->pose_count(); ++k) frames_.push_back(arm_->pose(k));
  }
  static void TearDownTestSuite() {
    arm_.reset();
    frames_.clear();
  }
  int new_faces(const Eigen::MatrixX3d& pose) const {
    return static_cast<int>(new_intersecting_faces(self_intersecting_faces(pose, arm_->faces()),
                                                   self_intersecting_faces(arm_->pose(0), arm_->faces()))
                                .size());
  }
  static std::unique_ptr<PoseSet> arm_;
  static std::vector<Eigen::MatrixX3d> frames_;
  std::unique_ptr<Device> device_ = make_cpu_device();
};

std::unique_ptr<PoseSet> ArmSequence::arm_;
std::vector<Eigen::MatrixX3d> ArmSequence::frames_;

TEST_F(ArmSequence, EveryFrameFreeAndTheCorrectionSmootherThanFrameByFrame) {
  SequenceReport report;
  std::vector<int> corrected_alone;
  SequenceCallbacks callbacks;
  callbacks.frame_corrected = [&](int frame, const Eigen::MatrixX3d&) { corrected_alone.push_back(frame); };
  const std::vector<FrameCorrection> results =
      correct_sequence(arm_->pose(0), frames_, arm_->faces(), *device_, {}, &report, callbacks);
  ASSERT_EQ(results.size(), frames_.size());
  EXPECT_EQ(corrected_alone, (std::vector<int>{8, 9, 10, 11, 12}));
  for (size_t t = 0; t < results.size(); ++t) {
    ASSERT_TRUE(results[t].error.empty()) << results[t].error;
    EXPECT_EQ(new_faces(results[t].vertices), 0) << "frame " << t;
    EXPECT_EQ(results[t].new_faces, 0) << "frame " << t;
  }
  // More than three standard deviations from every corrected frame: the target itself.
  for (const size_t t : {0u, 1u, 19u, 20u}) {
    EXPECT_FALSE(results[t].touched) << "frame " << t;
    EXPECT_TRUE((results[t].vertices.array() == frames_[t].array()).all()) << "frame " << t;
  }
  // The frame before the first contact already moves: the correction ramps in.
  EXPECT_TRUE(results[7].touched);
  EXPECT_FALSE(results[7].corrected);
  EXPECT_EQ(report.corrected_frames, 5);
  // Within the run of frames that need a correction, a later one carries its predecessor's.
  EXPECT_FALSE(results[8].carried);
  EXPECT_GE(report.carried_frames, 1);
  EXPECT_EQ(report.failed_frames, 0);
  EXPECT_EQ(report.frames_with_new_faces, 0);
  const SequenceCoherence& c = report.coherence;
  EXPECT_GT(c.vertices, 0);
  EXPECT_LT(c.largest_offset_change, c.largest_offset_change_alone);
  EXPECT_LT(c.acceleration_max_ratio, c.acceleration_max_ratio_alone);
  EXPECT_LE(c.acceleration_p99_ratio, c.acceleration_p99_ratio_alone);
}

TEST_F(ArmSequence, EarlierCorrectionsAreReusedAndNoSmoothingKeepsThem) {
  std::vector<Eigen::MatrixX3d> own(frames_.size());
  SequenceCallbacks keep;
  keep.frame_corrected = [&](int frame, const Eigen::MatrixX3d& pose) { own[static_cast<size_t>(frame)] = pose; };
  SequenceCorrectionOptions alone;
  alone.smoothing_frames = 0.0;
  const std::vector<FrameCorrection> first = correct_sequence(arm_->pose(0), frames_, arm_->faces(), *device_, alone, nullptr, keep);
  for (size_t t = 0; t < frames_.size(); ++t) {
    const Eigen::MatrixX3d& expected = own[t].size() != 0 ? own[t] : frames_[t];
    EXPECT_TRUE((first[t].vertices.array() == expected.array()).all()) << "frame " << t;
  }
  int recorrected = 0;
  SequenceCallbacks count;
  count.frame_corrected = [&](int, const Eigen::MatrixX3d&) { ++recorrected; };
  const std::vector<FrameCorrection> again =
      correct_sequence(arm_->pose(0), frames_, arm_->faces(), *device_, alone, nullptr, count, &own);
  EXPECT_EQ(recorrected, 0);
  for (size_t t = 0; t < frames_.size(); ++t) {
    EXPECT_TRUE((again[t].vertices.array() == first[t].vertices.array()).all()) << "frame " << t;
  }
}

TEST_F(ArmSequence, WithoutCarryingEveryFrameIsCorrectedItself) {
  SequenceCorrectionOptions options;
  options.carry_corrections = false;
  SequenceReport report;
  const std::vector<FrameCorrection> results =
      correct_sequence(arm_->pose(0), frames_, arm_->faces(), *device_, options, &report);
  EXPECT_EQ(report.carried_frames, 0);
  for (size_t t = 8; t <= 12; ++t) {
    EXPECT_FALSE(results[t].carried);
    EXPECT_FALSE(results[t].report.stages.empty()) << "frame " << t;
    EXPECT_EQ(new_faces(results[t].vertices), 0) << "frame " << t;
  }
}

TEST_F(ArmSequence, RejectsInconsistentInput) {
  std::vector<Eigen::MatrixX3d> frames = {frames_[0], frames_[1].topRows(10)};
  EXPECT_THROW(correct_sequence(arm_->pose(0), frames, arm_->faces(), *device_), ArgumentError);
  frames = {frames_[0]};
  frames[0](3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(correct_sequence(arm_->pose(0), frames, arm_->faces(), *device_), ArgumentError);
  EXPECT_THROW(correct_sequence(arm_->pose(0), {}, arm_->faces(), *device_), ArgumentError);
  SequenceCorrectionOptions negative;
  negative.smoothing_frames = -1.0;
  EXPECT_THROW(correct_sequence(arm_->pose(0), {frames_[0]}, arm_->faces(), *device_, negative), ArgumentError);
  const std::vector<Eigen::MatrixX3d> wrong_count(3);
  EXPECT_THROW(correct_sequence(arm_->pose(0), {frames_[0]}, arm_->faces(), *device_, {}, nullptr, {}, &wrong_count),
               ArgumentError);
}

}  // namespace
}  // namespace posekit::testing
