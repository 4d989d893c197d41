// summarize(): totals over per-particle statistics.
#include <posekit/device.hpp>

#include <gtest/gtest.h>

namespace posekit {
namespace {

Rk45ParticleStats particle(int accepted, int rejected, Rk45Status status) {
  Rk45ParticleStats stats;
  stats.accepted_steps = accepted;
  stats.rejected_steps = rejected;
  stats.rhs_evaluations = 1 + 6 * (accepted + rejected);
  stats.status = status;
  return stats;
}

TEST(Rk45Summary, EmptyBatchSumsToZero) {
  const Rk45Summary summary = summarize({});
  EXPECT_EQ(summary.accepted_steps, 0);
  EXPECT_EQ(summary.rejected_steps, 0);
  EXPECT_EQ(summary.rhs_evaluations, 0);
  EXPECT_EQ(summary.failures, 0);
}

TEST(Rk45Summary, AddsStepsAndCountsEveryFailureKind) {
  const Rk45Summary summary =
      summarize({particle(10, 2, Rk45Status::ok), particle(3, 0, Rk45Status::max_steps),
                 particle(0, 1, Rk45Status::step_underflow), particle(0, 0, Rk45Status::non_finite),
                 particle(7, 1, Rk45Status::ok)});
  EXPECT_EQ(summary.accepted_steps, 20);
  EXPECT_EQ(summary.rejected_steps, 4);
  EXPECT_EQ(summary.rhs_evaluations, 5 + 6 * 24);
  EXPECT_EQ(summary.failures, 3);
}

TEST(Rk45Summary, TotalsDoNotOverflowThirtyTwoBits) {
  Rk45ParticleStats large;
  large.accepted_steps = 1000000000;
  large.rhs_evaluations = 2000000000;
  const Rk45Summary summary = summarize(std::vector<Rk45ParticleStats>(3, large));
  EXPECT_EQ(summary.accepted_steps, 3000000000LL);
  EXPECT_EQ(summary.rhs_evaluations, 6000000000LL);
}

}  // namespace
}  // namespace posekit
