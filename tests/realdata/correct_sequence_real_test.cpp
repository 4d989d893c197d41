// The captured crane sequence corrected as one animation against crane-0014: every frame free of
// new intersecting faces and reproduced up to a median distance of 1e-3 of the diagonal, frames the
// correction does not reach copied exactly, and the corrected vertices accelerating at most 2 % more
// (99th percentile) and 5 % more (maximum) than in the captured motion.
#include <posekit/correct_sequence.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace posekit {
namespace {

TEST(CorrectRealSequence, CraneFramesFreeAndCoherentInTime) {
  std::vector<std::filesystem::path> files;
  for (int frame = 0; frame < 175; ++frame) {
    char name[48];
    std::snprintf(name, sizeof name, "crane-sequence/crane-%04d.obj", frame);
    const std::optional<std::filesystem::path> file = testing::shared_pose(name);
    if (!file) GTEST_SKIP() << "the crane sequence is not in the shared data (" << name << ")";
    files.push_back(*file);
  }
  const Mesh reference = read_mesh(*testing::shared_pose("crane-sequence/crane-0014.obj"));
  std::vector<Eigen::MatrixX3d> frames;
  for (const std::filesystem::path& file : files) frames.push_back(read_mesh(file).vertices);
  const std::unique_ptr<Device> device = make_cpu_device();
  SequenceReport report;
  const std::vector<FrameCorrection> results =
      correct_sequence(reference.vertices, frames, reference.faces, *device, {}, &report);
  const std::vector<int> reference_faces = self_intersecting_faces(reference.vertices, reference.faces);
  const double diagonal = report.bounding_box_diagonal;
  for (size_t t = 0; t < results.size(); ++t) {
    const FrameCorrection& frame = results[t];
    ASSERT_TRUE(frame.error.empty()) << files[t] << ": " << frame.error;
    EXPECT_TRUE(new_intersecting_faces(self_intersecting_faces(frame.vertices, reference.faces), reference_faces).empty())
        << files[t];
    EXPECT_LT(frame.median_distance_to_target, 1e-3 * diagonal) << files[t];
    if (!frame.touched) {
      EXPECT_TRUE((frame.vertices.array() == frames[t].array()).all()) << files[t];
    }
  }
  const SequenceCoherence& c = report.coherence;
  EXPECT_LE(c.acceleration_p99_ratio, 1.02);
  EXPECT_LE(c.acceleration_max_ratio, 1.05);
  EXPECT_LT(c.largest_offset_change, c.largest_offset_change_alone);
  std::printf("crane sequence: %d frames, %d corrected (%d carried), p99 %.4f max %.4f, offset change %.4f (alone %.4f), %.1f s\n",
              report.frames, report.corrected_frames, report.carried_frames, c.acceleration_p99_ratio,
              c.acceleration_max_ratio, c.largest_offset_change, c.largest_offset_change_alone, report.seconds);
}

}  // namespace
}  // namespace posekit
