// The kernels are written for 2, 4 or 8 doubles per vector; the device picks one from the
// hardware. Every width must give the reference's results, including center and point counts
// that are not multiples of the width.
#include "conformance.hpp"
#include "opencl_test_device.hpp"
#include "reference.hpp"

#include <gtest/gtest.h>

#include <string>

namespace posekit::opencl {
namespace {

using conformance::PaddedBlock;
using conformance::PaddedRows;
using conformance::Random;
using conformance::StridedPoints;

class VectorWidth : public ::testing::TestWithParam<int> {
 protected:
  std::unique_ptr<Device> device() const {
    OpenClDeviceOptions options;
    options.vector_width = GetParam();
    return make_opencl_device(options);
  }
};

TEST_P(VectorWidth, AssemblyMatchesTheReference) {
  POSEKIT_REQUIRE_OPENCL();
  Random random(41);
  const Points4 points = random.points(37);
  const Points4 centers = random.points(13);
  const conformance::reference::Assembly expected =
      conformance::reference::assemble(points, centers, true);
  PaddedBlock output(points.rows(), expected.block.cols());
  device()->assemble_rbf_block(StridedPoints(points).view(), StridedPoints(centers).view(), true,
                               output.inner());
  EXPECT_TRUE(output.untouched());
  EXPECT_TRUE(conformance::expect_near(output.value(), expected.block, expected.magnitude,
                                       conformance::kEntryTolerance));
}

TEST_P(VectorWidth, EvaluationMatchesTheReference) {
  POSEKIT_REQUIRE_OPENCL();
  Random random(42);
  for (const Eigen::Index centers : {1, 3, 7, 9, 1031}) {
    SCOPED_TRACE(std::to_string(centers) + " centers");
    const RbfField field = random.field(random.points(centers), 1.0, 1.0);
    const Points4 points = random.points(29);
    const std::unique_ptr<Device> opencl = device();
    PaddedRows output(Eigen::MatrixX3d::Zero(points.rows(), 3));
    opencl->evaluate_rbf(*opencl->upload_field(field), StridedPoints(points).view(),
                         output.inner());
    EXPECT_TRUE(output.untouched());
    const conformance::reference::Evaluation expected =
        conformance::reference::evaluate(field, points);
    EXPECT_TRUE(conformance::expect_near(output.value(), expected.values, expected.magnitude,
                                         conformance::kSumTolerance));
  }
}

TEST_P(VectorWidth, IntegrationMatchesTheReference) {
  POSEKIT_REQUIRE_OPENCL();
  Random random(43);
  const RbfField field = random.field(random.ball_points(61), 0.02, 0.02);
  const Eigen::MatrixX3d start = random.ball_points(17).leftCols<3>();
  Rk45Options options;
  options.relative_tolerance = 1e-9;
  options.absolute_tolerance = 1e-11;
  const std::unique_ptr<Device> opencl = device();
  Eigen::MatrixX3d positions = start;
  const std::vector<Rk45ParticleStats> stats =
      opencl->integrate_rk45(*opencl->upload_field(field), positions, options);
  const conformance::reference::Integration expected =
      conformance::reference::integrate(field, start, options);
  // The conformance suite's bound: 100 times the per-step tolerance.
  const conformance::Tolerance tolerance{100 * options.absolute_tolerance,
                                         100 * options.relative_tolerance};
  EXPECT_TRUE(conformance::expect_near(positions, expected.positions, Eigen::MatrixXd(), tolerance));
  ASSERT_EQ(stats.size(), expected.stats.size());
  for (std::size_t i = 0; i < stats.size(); ++i) {
    EXPECT_EQ(stats[i].status, expected.stats[i].status) << i;
    EXPECT_NEAR(stats[i].accepted_steps, expected.stats[i].accepted_steps, 1) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Doubles, VectorWidth, ::testing::Values(2, 4, 8),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return "width" + std::to_string(info.param);
                         });

}  // namespace
}  // namespace posekit::opencl
