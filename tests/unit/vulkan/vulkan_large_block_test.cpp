// An assembled block larger than one storage buffer of the device may be (128 MiB on lavapipe):
// split into rectangles, it must come out whole and equal to the CPU reference.
#include "vulkan_test_support.hpp"

#include <posekit/cpu_device.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>

namespace posekit::vulkan {
namespace {

TEST(VulkanLargeBlock, AssemblyBeyondOneStorageBuffer) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  const Eigen::Index rows = 4111;
  const Eigen::Index centers = 4096;
  const Eigen::Index columns = centers + kRbfPolynomialTerms;
  const auto bytes = static_cast<std::uint64_t>(rows * columns) * sizeof(double);
  const std::uint64_t limit = device->context()->limits().maxStorageBufferRange;
  // Larger than one storage buffer of lavapipe; on devices with larger buffers, still larger than
  // the ranges the device uses per dispatch.
  ASSERT_GT(bytes, std::min<std::uint64_t>(limit, std::uint64_t{128} << 20));
  ASSERT_GT(bytes, device->chunk_bytes());

  std::mt19937_64 engine(99);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  Points4 points(rows, 4);
  Points4 center_set(centers, 4);
  for (Eigen::Index i = 0; i < points.size(); ++i) points.data()[i] = coordinate(engine);
  for (Eigen::Index i = 0; i < center_set.size(); ++i) center_set.data()[i] = coordinate(engine);
  // A strided destination, as when the block is part of a larger system matrix.
  Eigen::MatrixXd system = Eigen::MatrixXd::Constant(rows + 2, columns, -5.0);
  device->assemble_rbf_block(points, center_set, true, system.middleRows(1, rows));
  Eigen::MatrixXd expected(rows, columns);
  make_cpu_device()->assemble_rbf_block(points, center_set, true, expected);

  EXPECT_TRUE((system.row(0).array() == -5.0).all() && (system.row(rows + 1).array() == -5.0).all())
      << "rows outside the block were written";
  long long mismatches = 0;
  for (Eigen::Index j = 0; j < columns; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) {
      const double r2 = j < centers ? (points.row(i) - center_set.row(j)).squaredNorm() : 0.0;
      const double scale = std::max(std::abs(expected(i, j)), r2);
      if (!(std::abs(system(i + 1, j) - expected(i, j)) <= 1e-13 * scale)) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0) << "of " << rows * columns << " entries";
}

}  // namespace
}  // namespace posekit::vulkan
