// The CPU backend's own guarantees, beyond the conformance suite that every backend passes: every
// compiled instruction set agrees with a plain reference, results do not depend on the number of
// threads, and the device describes itself.
#include <posekit/cpu_device.hpp>
#include <posekit/error.hpp>

#include "cpu/cpu_device.hpp"
#include "cpu/kernel_isa.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace posekit {
namespace {

Points4 random_points(std::mt19937_64& engine, Eigen::Index count) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  Points4 points(count, 4);
  for (Eigen::Index i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) points(i, k) = coordinate(engine);
    points(i, 3) = 0.5 * (coordinate(engine) + 1.0);
  }
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

long double reference_phi(double r2) {
  return r2 == 0.0 ? 0.0L : 0.5L * r2 * std::log(static_cast<long double>(r2));
}

// Field values in long double and, per entry, the sum of |terms| that the tolerance scales with.
void reference_values(const RbfField& field, const Points4& points, Eigen::MatrixX3d& values,
                      Eigen::MatrixX3d& magnitude) {
  values.resize(points.rows(), 3);
  magnitude.resize(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double x = points(i, 0), y = points(i, 1), z = points(i, 2), t = points(i, 3);
    const long double basis[15] = {1,     x,     y,     z,     t,     x * x, x * y, x * z,
                                   x * t, y * y, y * z, y * t, z * z, z * t, t * t};
    for (int c = 0; c < 3; ++c) {
      long double sum = 0, absolute = 0;
      for (Eigen::Index j = 0; j < field.centers.rows(); ++j) {
        const double r2 = (points.row(i) - field.centers.row(j)).squaredNorm();
        const long double phi = reference_phi(r2);
        sum += field.weights(j, c) * phi;
        absolute += std::abs(field.weights(j, c)) * std::max<long double>(std::abs(phi), r2);
      }
      for (int k = 0; k < 15; ++k) {
        sum += field.polynomial(k, c) * basis[k];
        absolute += std::abs(field.polynomial(k, c) * basis[k]);
      }
      values(i, c) = static_cast<double>(sum);
      magnitude(i, c) = static_cast<double>(absolute);
    }
  }
}

class CpuInstructionSet : public ::testing::TestWithParam<cpu::KernelIsa> {
 protected:
  void SetUp() override {
    if (!cpu::is_supported(GetParam())) {
      GTEST_SKIP() << "this processor or build has no " << cpu::to_string(GetParam()) << " kernels";
    }
    device_ = cpu::make_cpu_device(2, GetParam());
  }
  std::unique_ptr<Device> device_;
};

TEST_P(CpuInstructionSet, EvaluationMatchesTheReference) {
  std::mt19937_64 engine(101);
  const RbfField field = random_field(engine, 1031, 1.0);
  const Points4 points = random_points(engine, 257);
  Eigen::MatrixX3d expected, magnitude;
  reference_values(field, points, expected, magnitude);
  Eigen::MatrixX3d values(points.rows(), 3);
  device_->evaluate_rbf(*device_->upload_field(field), points, values);
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    // Sums over 1031 centers in another order: see tests/conformance/conformance.hpp.
    ASSERT_LE(std::abs(values.data()[i] - expected.data()[i]), 1e-12 * magnitude.data()[i])
        << "entry " << i;
  }
}

// The sum's order is part of the kernel (rbf_evaluation.cpp): center j in lane j mod 8 over whole
// blocks of eight, the rest in lane 0 with fused multiply-adds, the lanes added 0 to 7. Rebuilt here
// from the same copy's phi values (its assembly kernel), the field's values must match bit for bit,
// whatever the copy's vector width; the copies with FMA fuse every product into its lane.
TEST_P(CpuInstructionSet, SumsOverCentersInEightLanes) {
  std::mt19937_64 engine(105);
  RbfField field = random_field(engine, 1031, 1.0);  // 128 blocks of eight and 7 more
  field.polynomial.setZero();
  const Points4 points = random_points(engine, 67);
  Eigen::MatrixXd phi(points.rows(), field.centers.rows() + 15);
  device_->assemble_rbf_block(points, field.centers, true, phi);
  Eigen::MatrixX3d values(points.rows(), 3);
  device_->evaluate_rbf(*device_->upload_field(field), points, values);
  const bool fused = GetParam() != cpu::KernelIsa::baseline;
  const Eigen::Index whole_blocks_end = field.centers.rows() / 8 * 8;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (int c = 0; c < 3; ++c) {
      double lanes[8] = {};
      for (Eigen::Index j = 0; j < field.centers.rows(); ++j) {
        const bool in_block = j < whole_blocks_end;
        double& lane = lanes[in_block ? j % 8 : 0];
        const double term_phi = phi(i, j), weight = field.weights(j, c);
        lane = (fused || !in_block) ? std::fma(term_phi, weight, lane) : lane + term_phi * weight;
      }
      double expected = 0.0;
      for (const double lane : lanes) expected += lane;
      ASSERT_EQ(values(i, c), expected) << "point " << i << ", component " << c;
    }
  }
}

TEST_P(CpuInstructionSet, AssemblyMatchesTheReference) {
  std::mt19937_64 engine(102);
  const Points4 points = random_points(engine, 1031);  // not a multiple of any vector width
  Points4 centers = random_points(engine, 13);
  centers.row(3) = points.row(5);  // phi(0) = 0 exactly
  Eigen::MatrixXd block(points.rows(), centers.rows() + 15);
  device_->assemble_rbf_block(points, centers, true, block);
  EXPECT_EQ(block(5, 3), 0.0);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (Eigen::Index j = 0; j < centers.rows(); ++j) {
      const double r2 = (points.row(i) - centers.row(j)).squaredNorm();
      const long double expected = reference_phi(r2);
      ASSERT_LE(std::abs(block(i, j) - expected),
                1e-13 * std::max<long double>(std::abs(expected), r2))
          << "entry (" << i << ", " << j << ")";
    }
    EXPECT_EQ(block(i, centers.rows() + 8), points(i, 0) * points(i, 3)) << "x t column";
  }
}

TEST_P(CpuInstructionSet, IntegrationMatchesTheBaselineKernels) {
  std::mt19937_64 engine(103);
  const RbfField field = random_field(engine, 257, 0.02);
  const Eigen::MatrixX3d start = random_points(engine, 31).leftCols<3>();
  const std::unique_ptr<Device> baseline = cpu::make_cpu_device(1, cpu::KernelIsa::baseline);
  Eigen::MatrixX3d expected = start;
  const auto expected_stats =
      baseline->integrate_rk45(*baseline->upload_field(field), expected, Rk45Options());
  Eigen::MatrixX3d actual = start;
  const auto stats = device_->integrate_rk45(*device_->upload_field(field), actual, Rk45Options());
  ASSERT_EQ(stats.size(), expected_stats.size());
  for (std::size_t i = 0; i < stats.size(); ++i) {
    EXPECT_EQ(stats[i].status, Rk45Status::ok);
    EXPECT_NEAR(stats[i].accepted_steps, expected_stats[i].accepted_steps, 1) << "particle " << i;
  }
  // Both within the tolerance-driven global error of the same trajectories.
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Kernels, CpuInstructionSet,
                         ::testing::Values(cpu::KernelIsa::baseline, cpu::KernelIsa::avx2,
                                           cpu::KernelIsa::avx512),
                         [](const ::testing::TestParamInfo<cpu::KernelIsa>& info) {
                           return std::string(cpu::to_string(info.param));
                         });

TEST(CpuDevice, ResultsDoNotDependOnTheNumberOfThreads) {
  std::mt19937_64 engine(104);
  const RbfField field = random_field(engine, 129, 0.02);
  const Points4 points = random_points(engine, 20011);
  const Eigen::MatrixX3d start = points.topRows(203).leftCols<3>();
  Eigen::MatrixX3d values_1(points.rows(), 3), values_2(points.rows(), 3);
  Eigen::MatrixXd block_1(points.rows(), 129 + 15), block_2(points.rows(), 129 + 15);
  Eigen::MatrixX3d end_1 = start, end_2 = start;
  const std::unique_ptr<Device> one = make_cpu_device(1);
  const std::unique_ptr<Device> two = make_cpu_device(2);
  one->evaluate_rbf(*one->upload_field(field), points, values_1);
  two->evaluate_rbf(*two->upload_field(field), points, values_2);
  one->assemble_rbf_block(points, field.centers, true, block_1);
  two->assemble_rbf_block(points, field.centers, true, block_2);
  const auto stats_1 = one->integrate_rk45(*one->upload_field(field), end_1, Rk45Options());
  const auto stats_2 = two->integrate_rk45(*two->upload_field(field), end_2, Rk45Options());
  // Each value is computed by one thread in a fixed order: bit for bit the same.
  EXPECT_TRUE(values_1 == values_2);
  EXPECT_TRUE(block_1 == block_2);
  EXPECT_TRUE(end_1 == end_2);
  const Rk45Summary summary_1 = summarize(stats_1), summary_2 = summarize(stats_2);
  EXPECT_EQ(summary_1.accepted_steps, summary_2.accepted_steps);
  EXPECT_EQ(summary_1.rhs_evaluations, summary_2.rhs_evaluations);
  EXPECT_EQ(summary_2.failures, 0);
}

TEST(CpuDevice, DescribesItselfWithThreadsAndKernels) {
  const DeviceInfo info = make_cpu_device(1)->info();
  EXPECT_EQ(info.backend, "cpu");
  EXPECT_TRUE(info.fp64);
  EXPECT_EQ(info.compute_units, 1);
  EXPECT_NE(info.name.find(" x 1 thread"), std::string::npos) << info.name;
  EXPECT_NE(info.driver.find(cpu::to_string(cpu::best_supported_isa())), std::string::npos)
      << info.driver;
  const int all = make_cpu_device(0)->info().compute_units;
  EXPECT_GE(all, 1);
  EXPECT_EQ(make_cpu_device(all + 1)->info().compute_units, all)
      << "capped at the hardware threads";
}

TEST(CpuDevice, FieldsCarryTheNumberOfTheirDevice) {
  const std::unique_ptr<Device> first = make_cpu_device();
  const std::unique_ptr<Device> second = make_cpu_device();
  EXPECT_NE(first->id(), second->id());
  RbfField field;
  field.centers = Points4::Zero(3, 4);
  field.weights = Eigen::MatrixX3d::Zero(3, 3);
  const std::unique_ptr<DeviceField> uploaded = second->upload_field(field);
  EXPECT_EQ(uploaded->device_id(), second->id());
  EXPECT_EQ(uploaded->center_count(), 3);
}

TEST(CpuDevice, RejectsANegativeThreadCount) {
  try {
    make_cpu_device(-2);
    FAIL() << "no exception";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("threads"), std::string::npos) << error.what();
  }
}

TEST(CpuDevice, BestInstructionSetIsSupported) {
  EXPECT_TRUE(cpu::is_supported(cpu::KernelIsa::baseline));
  EXPECT_TRUE(cpu::is_supported(cpu::best_supported_isa()));
  for (cpu::KernelIsa isa : {cpu::KernelIsa::avx2, cpu::KernelIsa::avx512}) {
    if (cpu::is_supported(isa)) continue;
    EXPECT_THROW(cpu::make_cpu_device(1, isa), ArgumentError) << cpu::to_string(isa);
  }
}

}  // namespace
}  // namespace posekit
