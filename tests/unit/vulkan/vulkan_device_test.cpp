// The Vulkan device beyond the conformance cases: what it reports, and the splitting that lets any
// size run within the device's limits (rectangles of the assembled block, batches of points and
// particles, fields with more centers than the uniform buffers hold), each against the CPU
// reference backend.
#include "vulkan_test_support.hpp"

#include "vulkan/loop_budget.hpp"
#include "vulkan/shader_interface.hpp"
#include "vulkan/vulkan_discovery.hpp"

#include <posekit/cpu_device.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

namespace posekit::vulkan {
namespace {

Points4 random_points(std::mt19937_64& engine, Eigen::Index count, double scale = 1.0) {
  std::uniform_real_distribution<double> coordinate(-scale, scale);
  Points4 points(count, 4);
  for (Eigen::Index i = 0; i < points.size(); ++i) points.data()[i] = coordinate(engine);
  return points;
}

RbfField random_field(std::mt19937_64& engine, Eigen::Index centers, double weight_scale) {
  std::uniform_real_distribution<double> weight(-weight_scale, weight_scale);
  RbfField field;
  field.centers = random_points(engine, centers);
  field.weights.resize(centers, 3);
  for (Eigen::Index i = 0; i < field.weights.size(); ++i) field.weights.data()[i] = weight(engine);
  for (Eigen::Index i = 0; i < field.polynomial.size(); ++i)
    field.polynomial.data()[i] = weight(engine);
  return field;
}

double squared_distance(const Points4& a, Eigen::Index i, const Points4& b, Eigen::Index j) {
  return (a.row(i) - b.row(j)).squaredNorm();
}

// Entry (i, j) of two assembled blocks agrees to 1e-13 of max(|phi|, r^2) (the conformance
// suite's bound for single values).
::testing::AssertionResult blocks_agree(const Eigen::MatrixXd& actual,
                                        const Eigen::MatrixXd& expected, const Points4& points,
                                        const Points4& centers) {
  for (Eigen::Index j = 0; j < expected.cols(); ++j) {
    for (Eigen::Index i = 0; i < expected.rows(); ++i) {
      const double scale =
          std::max(std::abs(expected(i, j)),
                   j < centers.rows() ? squared_distance(points, i, centers, j) : 0.0);
      if (!(std::abs(actual(i, j) - expected(i, j)) <= 1e-13 * scale)) {
        return ::testing::AssertionFailure() << "entry (" << i << ", " << j << "): " << actual(i, j)
                                             << " vs the CPU's " << expected(i, j);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

// Field values agree to 1e-12 of the sum of the terms' sizes (the conformance suite's bound).
::testing::AssertionResult values_agree(const Eigen::MatrixX3d& actual,
                                        const Eigen::MatrixX3d& expected, const RbfField& field,
                                        const Points4& points) {
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    Eigen::Vector3d magnitude = Eigen::Vector3d::Zero();
    for (Eigen::Index j = 0; j < field.centers.rows(); ++j) {
      const double r2 = squared_distance(points, i, field.centers, j);
      const double phi = r2 == 0.0 ? 0.0 : 0.5 * r2 * std::log(r2);
      magnitude += field.weights.row(j).transpose().cwiseAbs() * std::max(std::abs(phi), r2);
    }
    const double p[4] = {points(i, 0), points(i, 1), points(i, 2), points(i, 3)};
    const double basis[15] = {1,           p[0],        p[1],        p[2],        p[3],
                              p[0] * p[0], p[0] * p[1], p[0] * p[2], p[0] * p[3], p[1] * p[1],
                              p[1] * p[2], p[1] * p[3], p[2] * p[2], p[2] * p[3], p[3] * p[3]};
    for (int k = 0; k < 15; ++k)
      magnitude += (field.polynomial.row(k).transpose() * basis[k]).cwiseAbs();
    for (int c = 0; c < 3; ++c) {
      if (!(std::abs(actual(i, c) - expected(i, c)) <= 1e-12 * magnitude(c))) {
        return ::testing::AssertionFailure() << "value (" << i << ", " << c << "): " << actual(i, c)
                                             << " vs the CPU's " << expected(i, c);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

// End positions within 100 times the per-step tolerance of the CPU's (the conformance suite's
// bound), statuses equal and step counts within one.
::testing::AssertionResult integrations_agree(const Eigen::MatrixX3d& actual,
                                              const std::vector<Rk45ParticleStats>& actual_stats,
                                              const Eigen::MatrixX3d& expected,
                                              const std::vector<Rk45ParticleStats>& expected_stats,
                                              const Rk45Options& options) {
  for (Eigen::Index i = 0; i < actual.rows(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double allowed = 100.0 * (options.absolute_tolerance +
                                      options.relative_tolerance * std::abs(expected(i, c)));
      if (!(std::abs(actual(i, c) - expected(i, c)) <= allowed)) {
        return ::testing::AssertionFailure() << "particle " << i << ", component " << c << ": "
                                             << actual(i, c) << " vs the CPU's " << expected(i, c);
      }
    }
    const Rk45ParticleStats& a = actual_stats[static_cast<std::size_t>(i)];
    const Rk45ParticleStats& b = expected_stats[static_cast<std::size_t>(i)];
    if (a.status != b.status || std::abs(a.accepted_steps - b.accepted_steps) > 1 ||
        std::abs(a.rejected_steps - b.rejected_steps) > 1) {
      return ::testing::AssertionFailure()
             << "particle " << i << ": " << a.accepted_steps << " accepted, " << a.rejected_steps
             << " rejected, status " << static_cast<int>(a.status)
             << "; the CPU: " << b.accepted_steps << ", " << b.rejected_steps << ", "
             << static_cast<int>(b.status);
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(VulkanDevice, DescribesThePhysicalDeviceAndDriver) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  const DeviceInfo info = device->info();
  const Discovery discovery = discover_device();
  ASSERT_TRUE(discovery.device.has_value()) << discovery.reason;
  EXPECT_EQ(info.backend, "vulkan");
  EXPECT_EQ(info.name, discovery.device->device_name);
  EXPECT_EQ(info.driver, discovery.device->driver);
  EXPECT_FALSE(info.driver.empty());
  EXPECT_TRUE(info.fp64);
  EXPECT_EQ(info.emulated_on_cpu, discovery.device->is_cpu);
  if (info.name.find("llvmpipe") != std::string::npos) {
    EXPECT_TRUE(info.emulated_on_cpu) << "lavapipe runs on the CPU";
  }
  EXPECT_EQ(info.max_buffer_bytes, device->context()->limits().maxStorageBufferRange);
  for (const BackendStatus& status : list_backends()) {
    if (status.name != "vulkan") continue;
    EXPECT_EQ(status.state, BackendState::available) << status.reason;
    EXPECT_EQ(status.info.name, info.name);
    EXPECT_EQ(status.info.driver, info.driver);
  }
}

TEST(VulkanDevice, RejectsTuningsTooSmallForOnePoint) {
  std::string reason;
  if (!testing::make_validated_device(reason)) GTEST_SKIP() << reason;
  EXPECT_THROW(VulkanDevice(true, DeviceTuning{32, 0}), ArgumentError);
  EXPECT_THROW(VulkanDevice(true, DeviceTuning{0, 100}), ArgumentError);
}

TEST(VulkanDevice, AssemblesInRectanglesOfEveryShape) {
  // 4 KiB per storage range: 128 points per row block and at most 128 / rows-in-block columns,
  // so that row blocks, column runs, runs with centers and polynomial terms mixed and runs of
  // polynomial terms alone all occur, and the two command slots alternate.
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device, DeviceTuning{4096, 0});
  const std::unique_ptr<Device> cpu = make_cpu_device();
  std::mt19937_64 engine(11);
  for (const auto& [rows, centers] :
       {std::pair<Eigen::Index, Eigen::Index>{301, 77}, {129, 1}, {5, 300}}) {
    const Points4 points = random_points(engine, rows);
    const Points4 center_set = random_points(engine, centers);
    for (bool with_polynomial : {true, false}) {
      const Eigen::Index columns = centers + (with_polynomial ? kRbfPolynomialTerms : 0);
      Eigen::MatrixXd actual = Eigen::MatrixXd::Constant(rows, columns, -7.0);
      Eigen::MatrixXd expected(rows, columns);
      device->assemble_rbf_block(points, center_set, with_polynomial, actual);
      cpu->assemble_rbf_block(points, center_set, with_polynomial, expected);
      EXPECT_TRUE(blocks_agree(actual, expected, points, center_set))
          << rows << " points, " << centers << " centers, polynomial " << with_polynomial;
    }
  }
}

TEST(VulkanDevice, EvaluatesAndIntegratesInBatches) {
  // 4 KiB per storage range: 128 points or particles per dispatch.
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device, DeviceTuning{4096, 0});
  const std::unique_ptr<Device> cpu = make_cpu_device();
  std::mt19937_64 engine(12);
  const RbfField field = random_field(engine, 37, 0.02);
  const Points4 points = random_points(engine, 1000);
  const std::unique_ptr<DeviceField> on_device = device->upload_field(field);
  const std::unique_ptr<DeviceField> on_cpu = cpu->upload_field(field);
  Eigen::MatrixX3d actual(1000, 3);
  Eigen::MatrixX3d expected(1000, 3);
  device->evaluate_rbf(*on_device, points, actual);
  cpu->evaluate_rbf(*on_cpu, points, expected);
  EXPECT_TRUE(values_agree(actual, expected, field, points));

  const Rk45Options options;
  Eigen::MatrixX3d moved = points.topRows(300).leftCols<3>();
  Eigen::MatrixX3d reference = moved;
  const std::vector<Rk45ParticleStats> stats = device->integrate_rk45(*on_device, moved, options);
  const std::vector<Rk45ParticleStats> reference_stats =
      cpu->integrate_rk45(*on_cpu, reference, options);
  EXPECT_TRUE(integrations_agree(moved, stats, reference, reference_stats, options));
  EXPECT_GT((moved - points.topRows(300).leftCols<3>()).cwiseAbs().maxCoeff(), 1e-3)
      << "the field should move the particles";
}

TEST(VulkanDevice, FieldsBeyondTheUniformChunks) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  const std::unique_ptr<Device> cpu = make_cpu_device();
  std::mt19937_64 engine(13);
  const Eigen::Index centers = kUniformChunks * kCentersPerChunk + 1001;
  const RbfField field = random_field(engine, centers, 2e-4);
  const Points4 points = random_points(engine, 97);
  const std::unique_ptr<DeviceField> on_device = device->upload_field(field);
  const std::unique_ptr<DeviceField> on_cpu = cpu->upload_field(field);
  EXPECT_EQ(on_device->center_count(), centers);
  Eigen::MatrixX3d actual(97, 3);
  Eigen::MatrixX3d expected(97, 3);
  device->evaluate_rbf(*on_device, points, actual);
  cpu->evaluate_rbf(*on_cpu, points, expected);
  EXPECT_TRUE(values_agree(actual, expected, field, points));

  Rk45Options options;
  options.relative_tolerance = 1e-9;
  options.absolute_tolerance = 1e-11;
  Eigen::MatrixX3d moved = points.topRows(5).leftCols<3>();
  Eigen::MatrixX3d reference = moved;
  const std::vector<Rk45ParticleStats> stats = device->integrate_rk45(*on_device, moved, options);
  const std::vector<Rk45ParticleStats> reference_stats =
      cpu->integrate_rk45(*on_cpu, reference, options);
  EXPECT_TRUE(integrations_agree(moved, stats, reference, reference_stats, options));
}

TEST(VulkanDevice, SplitsWorkToStayWithinTheLoopBudget) {
  // A budget of 1,500 loop iterations per invocation: sums of at most 10,912 centers per
  // evaluation dispatch (so the 13,289 centers below take two, the second adding to the first),
  // and RK45 rounds of one step for the 37-center field (so every particle needs many rounds).
  const std::uint64_t budget = 1500;
  ASSERT_LT(centers_per_evaluation(budget), 13289U);
  ASSERT_EQ(rk45_steps_per_round(37, budget, 100000), 1U);
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device, DeviceTuning{0, budget});
  const std::unique_ptr<Device> cpu = make_cpu_device();
  std::mt19937_64 engine(14);

  const RbfField wide = random_field(engine, 13289, 2e-4);
  const Points4 points = random_points(engine, 61);
  Eigen::MatrixX3d actual(61, 3);
  Eigen::MatrixX3d expected(61, 3);
  device->evaluate_rbf(*device->upload_field(wide), points, actual);
  cpu->evaluate_rbf(*cpu->upload_field(wide), points, expected);
  EXPECT_TRUE(values_agree(actual, expected, wide, points));

  const RbfField small = random_field(engine, 37, 0.02);
  const Rk45Options options;
  Eigen::MatrixX3d moved = points.leftCols<3>();
  Eigen::MatrixX3d reference = moved;
  const std::vector<Rk45ParticleStats> stats =
      device->integrate_rk45(*device->upload_field(small), moved, options);
  const std::vector<Rk45ParticleStats> reference_stats =
      cpu->integrate_rk45(*cpu->upload_field(small), reference, options);
  EXPECT_TRUE(integrations_agree(moved, stats, reference, reference_stats, options));
  EXPECT_GT(stats.front().accepted_steps, 3) << "the particles should take several rounds";

  // Not even one step of a 13,289-center field fits 1,500 iterations: an error, not a result.
  Eigen::MatrixX3d unmoved = points.leftCols<3>();
  EXPECT_THROW(device->integrate_rk45(*device->upload_field(wide), unmoved, options), DeviceError);
  EXPECT_EQ(unmoved, points.leftCols<3>());
}

TEST(VulkanDevice, ALoopCutShortByTheDriverIsAnError) {
  // lavapipe stops the loops of an invocation after 65,535 iterations in all. Told that it may
  // loop without limit, the device runs into that stop: an RK45 round through 40,000 centers
  // (5,000 iterations per field value) ends within 13 field values, and an evaluation of 600,000
  // centers within one sum. The shaders notice the centers they missed.
  std::string reason;
  const std::unique_ptr<VulkanDevice> probe = testing::make_validated_device(reason);
  if (!probe) GTEST_SKIP() << reason;
  if (!probe->context()->description().loop_limited) {
    GTEST_SKIP() << probe->info().name << " does not limit loop iterations";
  }
  VulkanDevice device(true, DeviceTuning{0, kUnlimitedLoopIterations});
  std::mt19937_64 engine(15);
  Rk45Options options;
  options.relative_tolerance = 1e-12;
  options.absolute_tolerance = 1e-14;
  Eigen::MatrixX3d positions = random_points(engine, 3).leftCols<3>();
  EXPECT_THROW(device.integrate_rk45(*device.upload_field(random_field(engine, 40000, 1e-5)),
                                     positions, options),
               DeviceError);
  Eigen::MatrixX3d values(5, 3);
  EXPECT_THROW(device.evaluate_rbf(*device.upload_field(random_field(engine, 600000, 1e-6)),
                                   random_points(engine, 5), values),
               DeviceError);
}

}  // namespace
}  // namespace posekit::vulkan
