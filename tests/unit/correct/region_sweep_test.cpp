// The region sweep: a region whose repair failed is not tried again until something within reach
// of it has moved, and is tried again once something has.
#include "correct/region_sweep.hpp"

#include "bent_arm.hpp"
#include "correction_fixture.hpp"
#include <posekit/vertex_regions.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace posekit::detail {
namespace {

class RegionSweepTest : public ::testing::Test {
 protected:
  const PoseSet* arm_ = &posekit::testing::bent_arm(16, 150.0);
  testing::StageFixture fixture_{arm_->pose(0), arm_->pose(1), arm_->faces()};

  // Per face, the ring distance of its nearest corner from face `from`'s corners (-1 beyond `limit`).
  std::vector<int> face_distances(int from, int limit) const {
    const Eigen::MatrixX3i& faces = arm_->faces();
    const std::vector<int> distance = ring_distances(
        face_vertices({from}, faces, static_cast<size_t>(arm_->vertex_count())), fixture_.context.neighbours, limit);
    std::vector<int> nearest(static_cast<size_t>(faces.rows()), -1);
    for (int f = 0; f < faces.rows(); ++f) {
      for (int c = 0; c < 3; ++c) {
        const int d = distance[static_cast<size_t>(faces(f, c))];
        int& n = nearest[static_cast<size_t>(f)];
        if (d >= 0 && (n < 0 || d < n)) n = d;
      }
    }
    return nearest;
  }

  // `face` and the faces sharing a corner with it.
  std::vector<int> with_its_neighbours(int face) const {
    const std::vector<int> distance = face_distances(face, 1);
    std::vector<int> around;
    for (int f = 0; f < static_cast<int>(distance.size()); ++f) {
      if (distance[static_cast<size_t>(f)] == 0) around.push_back(f);
    }
    return around;
  }

  // Sweeps `kept_face` and `failing_face` with its neighbours (the faces to mend, for three rounds):
  // the region of `kept_face` is repaired (by a small move) the first time only, the other region,
  // the larger and so tried first, never. Returns how often the repair was asked for the other one.
  int attempts_on_failing_region(int kept_face, int failing_face) {
    RegionSweep sweep;
    sweep.rounds = 3;
    bool first = true;
    std::vector<int> to_mend = with_its_neighbours(failing_face);
    to_mend.push_back(kept_face);
    std::sort(to_mend.begin(), to_mend.end());
    sweep.goal.faces_to_mend = [&](const Candidate&) { return to_mend; };
    sweep.goal.improves = [&](const Probe&, const Candidate&) {
      const bool improves = first;
      first = false;
      return improves;
    };
    const int failing_corner = arm_->faces()(failing_face, 0);
    int attempts = 0;
    const RegionRepair repair = [&](const std::vector<int>& region, const Candidate& current) -> std::optional<Probe> {
      if (std::binary_search(region.begin(), region.end(), failing_corner)) {
        ++attempts;
        return std::nullopt;
      }
      Eigen::MatrixX3d moved = current.pose();
      moved.row(region.front()) *= 1.0 + 1e-6;
      return current.probe(std::move(moved));
    };
    Candidate candidate = fixture_.candidate(arm_->pose(1));
    const SweepOutcome outcome = sweep_regions(candidate, fixture_.context, sweep, repair);
    EXPECT_EQ(outcome.regions, 1);
    return attempts;
  }
};

TEST_F(RegionSweepTest, FailedRegionFarFromChangesIsNotTriedAgain) {
  const int end_face = 0;
  const std::vector<int> distance = face_distances(end_face, 1 << 20);
  const auto farthest = std::max_element(distance.begin(), distance.end());
  ASSERT_GT(*farthest, 16);
  EXPECT_EQ(attempts_on_failing_region(end_face, static_cast<int>(farthest - distance.begin())), 1);
}

TEST_F(RegionSweepTest, FailedRegionNearAChangeIsTriedAgain) {
  const int end_face = 0;
  const std::vector<int> distance = face_distances(end_face, 8);
  const auto near = std::find(distance.begin(), distance.end(), 5);
  ASSERT_NE(near, distance.end());
  // Round one: failed, then the other region kept; round two: the failed region lies within reach
  // of the move, so it is tried again (and the kept one, which no longer improves); no round three.
  EXPECT_EQ(attempts_on_failing_region(end_face, static_cast<int>(near - distance.begin())), 2);
}

}  // namespace
}  // namespace posekit::detail
