#include "correct/contact_separation.hpp"

#include "correction_fixture.hpp"
#include "two_spheres.hpp"

#include <posekit/self_intersections.hpp>

#include <gtest/gtest.h>

namespace posekit::detail {
namespace {

using posekit::testing::two_spheres;

// Pressed a fifth of their radius into each other, the spheres are pushed apart where they
// overlap, and their far sides keep the target's positions exactly.
TEST(ContactSeparation, SeparatesOverlappingPartsAndLeavesTheRestAlone) {
  const Mesh apart = two_spheres(3.0);
  const Mesh pressed = two_spheres(1.6);
  ASSERT_TRUE(self_intersecting_faces(apart.vertices, apart.faces).empty());
  const auto overlapping = static_cast<int>(self_intersecting_faces(pressed.vertices, pressed.faces).size());
  ASSERT_GT(overlapping, 0);
  const testing::StageFixture fixture(apart.vertices, pressed.vertices, apart.faces);
  const SeparationOutcome separation = separate_contacts(fixture.context, fixture.candidate(fixture.target));
  EXPECT_EQ(separation.new_faces_before, overlapping);
  EXPECT_EQ(separation.best.new_face_count(), 0);
  EXPECT_GT(separation.rounds, 0);
  EXPECT_TRUE(self_intersecting_faces(separation.best.pose(), apart.faces).empty());
  int unchanged = 0;
  for (Eigen::Index v = 0; v < pressed.vertices.rows(); ++v) {
    if (std::abs(pressed.vertices(v, 0)) > 0.5) {
      EXPECT_EQ(separation.best.pose().row(v), pressed.vertices.row(v)) << v;
    }
    if (separation.best.pose().row(v) == pressed.vertices.row(v)) ++unchanged;
  }
  EXPECT_GT(unchanged, pressed.vertices.rows() / 2);
}

// Intersections the reference has too are not the stage's to remove.
TEST(ContactSeparation, LeavesTheReferencesOwnIntersectionsAlone) {
  const Mesh pressed = two_spheres(1.6);
  const testing::StageFixture fixture(pressed.vertices, pressed.vertices, pressed.faces);
  const SeparationOutcome separation = separate_contacts(fixture.context, fixture.candidate(fixture.target));
  EXPECT_EQ(separation.new_faces_before, 0);
  EXPECT_EQ(separation.rounds, 0);
  EXPECT_EQ(separation.best.pose(), pressed.vertices);
}

}  // namespace
}  // namespace posekit::detail
