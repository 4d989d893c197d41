// Work larger than a buffer: a device limited to tiny buffers (4 KiB, through
// OpenClDeviceOptions::max_buffer_bytes) must cut every operation into many chunks and still give
// the reference's results; chunking points or particles alone must not change a single bit.
#include "conformance.hpp"
#include "opencl/chunking.hpp"
#include "opencl_test_device.hpp"
#include "reference.hpp"

#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace posekit::opencl {
namespace {

using conformance::kEntryTolerance;
using conformance::kSumTolerance;
using conformance::PaddedBlock;
using conformance::PaddedRows;
using conformance::Random;
using conformance::StridedPoints;

constexpr std::uint64_t kTinyBuffer = kMinimumBufferBytes;

std::unique_ptr<Device> tiny_buffer_device(int vector_width = 0) {
  OpenClDeviceOptions options;
  options.max_buffer_bytes = kTinyBuffer;
  options.vector_width = vector_width;
  return make_opencl_device(options);
}

TEST(SmallBuffers, DeviceReportsTheLimit) {
  POSEKIT_REQUIRE_OPENCL();
  EXPECT_EQ(tiny_buffer_device()->info().max_buffer_bytes, kTinyBuffer);
}

TEST(SmallBuffers, AssemblyInTilesMatchesTheReference) {
  POSEKIT_REQUIRE_OPENCL();
  for (const int width : {2, 8}) {
    SCOPED_TRACE("vector width " + std::to_string(width));
    const std::unique_ptr<Device> device = tiny_buffer_device(width);
    Random random(31);
    const Points4 points = random.points(1031);
    const Points4 centers = random.points(257);
    const Eigen::Index columns = centers.rows() + kRbfPolynomialTerms;
    // The test means nothing unless the block is cut both ways.
    const TileShape tile = assembly_tiles(chunk_limits(kTinyBuffer), points.rows(), columns, width);
    ASSERT_LT(tile.rows, points.rows());
    ASSERT_LT(tile.columns, columns);
    ASSERT_NE(centers.rows() % tile.columns, 0) << "a tile should hold centers and terms";

    const conformance::reference::Assembly expected =
        conformance::reference::assemble(points, centers, true);
    PaddedBlock output(points.rows(), columns);
    device->assemble_rbf_block(StridedPoints(points).view(), StridedPoints(centers).view(), true,
                               output.inner());
    EXPECT_TRUE(output.untouched());
    EXPECT_TRUE(conformance::expect_near(output.value(), expected.block, expected.magnitude,
                                         kEntryTolerance));
  }
}

TEST(SmallBuffers, EvaluationOfAFieldInPartsMatchesTheReference) {
  POSEKIT_REQUIRE_OPENCL();
  const std::unique_ptr<Device> device = tiny_buffer_device();
  Random random(32);
  const RbfField field = random.field(random.points(257), 1.0, 1.0);
  const Points4 points = random.points(1031);
  ASSERT_LT(items_per_chunk(chunk_limits(kTinyBuffer), 7 * sizeof(double), 2), field.centers.rows())
      << "the field should need several buffers";
  ASSERT_LT(items_per_chunk(chunk_limits(kTinyBuffer), 4 * sizeof(double), 1), points.rows())
      << "the points should need several chunks";

  const std::unique_ptr<DeviceField> uploaded = device->upload_field(field);
  EXPECT_EQ(uploaded->center_count(), field.centers.rows());
  PaddedRows output(Eigen::MatrixX3d::Zero(points.rows(), 3));
  device->evaluate_rbf(*uploaded, StridedPoints(points).view(), output.inner());
  EXPECT_TRUE(output.untouched());
  const conformance::reference::Evaluation expected =
      conformance::reference::evaluate(field, points);
  EXPECT_TRUE(conformance::expect_near(output.value(), expected.values, expected.magnitude,
                                       kSumTolerance));
}

TEST(SmallBuffers, ChunksOfPointsGiveTheSameBitsAsOneLaunch) {
  POSEKIT_REQUIRE_OPENCL();
  Random random(33);
  // 50 centers fit one 4 KiB buffer, so only the points are cut.
  const RbfField field = random.field(random.points(50), 1.0, 1.0);
  const Points4 points = random.points(1031);
  ASSERT_GE(items_per_chunk(chunk_limits(kTinyBuffer), 7 * sizeof(double), 8), field.centers.rows())
      << "the field should fit one buffer at any vector width";

  const std::unique_ptr<Device> whole = make_opencl_device();
  Eigen::MatrixX3d expected(points.rows(), 3);
  whole->evaluate_rbf(*whole->upload_field(field), points, expected);

  const std::unique_ptr<Device> chunked = tiny_buffer_device();
  Eigen::MatrixX3d actual(points.rows(), 3);
  chunked->evaluate_rbf(*chunked->upload_field(field), points, actual);
  EXPECT_EQ(actual, expected);
}

TEST(SmallBuffers, ChunksOfParticlesGiveTheSameBitsAsOneLaunch) {
  POSEKIT_REQUIRE_OPENCL();
  Random random(34);
  const RbfField field = random.field(random.ball_points(50), 0.02, 0.02);
  const Eigen::MatrixX3d start = random.ball_points(401).leftCols<3>();
  ASSERT_LT(items_per_chunk(chunk_limits(kTinyBuffer), 3 * sizeof(double), 1), start.rows())
      << "the particles should need several chunks";
  Rk45Options options;

  const std::unique_ptr<Device> whole = make_opencl_device();
  Eigen::MatrixX3d expected = start;
  const std::vector<Rk45ParticleStats> expected_stats =
      whole->integrate_rk45(*whole->upload_field(field), expected, options);

  const std::unique_ptr<Device> chunked = tiny_buffer_device();
  PaddedRows actual(start);
  const std::vector<Rk45ParticleStats> actual_stats =
      chunked->integrate_rk45(*chunked->upload_field(field), actual.inner(), options);
  EXPECT_TRUE(actual.untouched());
  EXPECT_EQ(actual.value(), expected);
  ASSERT_EQ(actual_stats.size(), expected_stats.size());
  for (std::size_t i = 0; i < actual_stats.size(); ++i) {
    EXPECT_EQ(actual_stats[i].accepted_steps, expected_stats[i].accepted_steps) << i;
    EXPECT_EQ(actual_stats[i].rejected_steps, expected_stats[i].rejected_steps) << i;
    EXPECT_EQ(actual_stats[i].rhs_evaluations, expected_stats[i].rhs_evaluations) << i;
    EXPECT_EQ(actual_stats[i].status, expected_stats[i].status) << i;
  }
  EXPECT_GT((expected - start).rowwise().norm().maxCoeff(), 1e-3) << "the field should move them";
}

TEST(SmallBuffers, IntegrationRefusesAFieldLargerThanOneBuffer) {
  POSEKIT_REQUIRE_OPENCL();
  const std::unique_ptr<Device> device = tiny_buffer_device();
  Random random(35);
  const RbfField field = random.field(random.ball_points(257), 0.02, 0.02);
  const std::unique_ptr<DeviceField> uploaded = device->upload_field(field);
  const Eigen::MatrixX3d start = random.ball_points(5).leftCols<3>();
  Eigen::MatrixX3d positions = start;
  try {
    device->integrate_rk45(*uploaded, positions, Rk45Options());
    ADD_FAILURE() << "no DeviceError for a field in several buffers";
  } catch (const DeviceError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("257 centers"), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(kTinyBuffer) + " bytes"), std::string::npos) << message;
  }
  EXPECT_EQ(positions, start);
}

}  // namespace
}  // namespace posekit::opencl
