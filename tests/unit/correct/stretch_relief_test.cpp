#include "correct/stretch_relief.hpp"

#include "correction_fixture.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace posekit::detail {
namespace {

constexpr int kRings = 60;
constexpr int kAround = 12;
constexpr double kSpacing = 0.1;
constexpr double kRadius = 0.1;

struct Tube {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  int vertex(int ring, int k) const { return ring * kAround + (k % kAround); }
};

// An open tube along z: kRings rings of kAround vertices, kSpacing apart.
Tube straight_tube() {
  Tube tube;
  tube.vertices.resize(kRings * kAround, 3);
  for (int ring = 0; ring < kRings; ++ring) {
    for (int k = 0; k < kAround; ++k) {
      const double angle = 2.0 * M_PI * k / kAround;
      tube.vertices.row(tube.vertex(ring, k)) << kRadius * std::cos(angle), kRadius * std::sin(angle), kSpacing * ring;
    }
  }
  tube.faces.resize(2 * (kRings - 1) * kAround, 3);
  int f = 0;
  for (int ring = 0; ring + 1 < kRings; ++ring) {
    for (int k = 0; k < kAround; ++k) {
      tube.faces.row(f++) << tube.vertex(ring, k), tube.vertex(ring, k + 1), tube.vertex(ring + 1, k);
      tube.faces.row(f++) << tube.vertex(ring, k + 1), tube.vertex(ring + 1, k + 1), tube.vertex(ring + 1, k);
    }
  }
  return tube;
}

// The tube with its first rings shifted by `shift` and its last ten left where they were.
Eigen::MatrixX3d with_tip_left_behind(const Tube& tube, const Eigen::RowVector3d& shift) {
  Eigen::MatrixX3d moved = tube.vertices;
  for (int v = 0; v < (kRings - 10) * kAround; ++v) moved.row(v) += shift;
  return moved;
}

// A limb moved sideways by a correction while its tip stayed where the target has it: the band of
// faces between them is torn, many times as long, and too far for the rings around it to spread.
// The tip is cut off from the rest by that band, so it moves with the limb, in the target's own
// shape, and no face stays stretched.
TEST(StretchRelief, ATipCutOffByATornBandMovesWithTheLimb) {
  const Tube tube = straight_tube();
  const Eigen::RowVector3d shift(5.0, 0.0, 0.0);
  const Eigen::MatrixX3d moved = with_tip_left_behind(tube, shift);
  const testing::StageFixture fixture(tube.vertices, tube.vertices, tube.faces);
  Candidate result = fixture.candidate(moved);
  ASSERT_EQ(result.new_face_count(), 0);
  ASSERT_GT(fixture.context.stretch.count(moved, kStronglyStretchedFactor), 0);

  const SweepOutcome relief = relieve_stretch(result, fixture.context);
  EXPECT_GE(relief.regions, 1);
  EXPECT_EQ(fixture.context.stretch.count(result.pose()), 0);
  EXPECT_EQ(result.new_face_count(), 0);
  // The tip's last ring went along with the limb, in the target's shape.
  for (int k = 0; k < kAround; ++k) {
    const int v = tube.vertex(kRings - 1, k);
    EXPECT_LT((result.pose().row(v) - (tube.vertices.row(v) + shift)).norm(), 1e-6) << v;
  }
  // The limb itself, far from the band, kept its place.
  EXPECT_EQ(result.pose().row(0), moved.row(0));
}

// The same tear over a shorter shift, which the rings around the band can spread: the tip stays
// where the target has it (a whole tail is not moved to spare a band that can be relieved alone).
TEST(StretchRelief, ATornBandRelievedAloneLeavesTheTip) {
  const Tube tube = straight_tube();
  const Eigen::MatrixX3d moved = with_tip_left_behind(tube, Eigen::RowVector3d(0.8, 0.0, 0.0));
  const testing::StageFixture fixture(tube.vertices, tube.vertices, tube.faces);
  Candidate result = fixture.candidate(moved);
  ASSERT_GT(fixture.context.stretch.count(moved, kStronglyStretchedFactor), 0);

  relieve_stretch(result, fixture.context);
  EXPECT_EQ(fixture.context.stretch.count(result.pose()), 0);
  for (int k = 0; k < kAround; ++k) {
    const int v = tube.vertex(kRings - 1, k);
    EXPECT_EQ(result.pose().row(v), moved.row(v)) << v;
  }
}

}  // namespace
}  // namespace posekit::detail
