// The CUDA device beyond the conformance suite: work cut into many chunks and tiles by a tiny
// scratch budget, threads that integrate many particles each, and a batch the size of a pose's
// constraints. Needs an NVIDIA GPU; skipped with the runtime's reason elsewhere.
#include "conformance.hpp"
#include "cuda/chunking.hpp"
#include "cuda_test_device.hpp"
#include "reference.hpp"

#include <posekit/cpu_device.hpp>
#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace posekit::cuda {
namespace {

using conformance::kEntryTolerance;
using conformance::kSumTolerance;
using conformance::PaddedBlock;
using conformance::PaddedRows;
using conformance::Random;
using conformance::StridedPoints;

std::unique_ptr<Device> tiny_chunk_device() {
  CudaDeviceOptions options;
  options.max_chunk_bytes = kMinimumChunkBytes;
  return make_cuda_device(options);
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

bool same_stats(const std::vector<Rk45ParticleStats>& a, const std::vector<Rk45ParticleStats>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].accepted_steps != b[i].accepted_steps || a[i].rejected_steps != b[i].rejected_steps ||
        a[i].rhs_evaluations != b[i].rhs_evaluations || a[i].status != b[i].status) {
      return false;
    }
  }
  return true;
}

TEST(CudaDevice, DescribesTheGpu) {
  POSEKIT_REQUIRE_CUDA();
  const Discovery discovery = discover_device();
  const std::unique_ptr<Device> device = make_cuda_device();
  const DeviceInfo info = device->info();
  EXPECT_EQ(info.backend, "cuda");
  EXPECT_EQ(info.name, discovery.device->device_name);
  EXPECT_TRUE(info.fp64);
  EXPECT_FALSE(info.emulated_on_cpu);
  EXPECT_GE(info.compute_units, 1);
  EXPECT_NE(info.driver.find("SMs at"), std::string::npos) << info.driver;
}

TEST(CudaDevice, AssemblyInTilesMatchesTheReference) {
  POSEKIT_REQUIRE_CUDA();
  const std::unique_ptr<Device> device = tiny_chunk_device();
  Random random(51);
  const Points4 points = random.points(1031);
  const Points4 centers = random.points(257);
  const Eigen::Index columns = centers.rows() + kRbfPolynomialTerms;
  // The test means nothing unless the block is cut both ways.
  const TileShape tile = assembly_tiles(chunk_limits(kMinimumChunkBytes), points.rows(), columns);
  ASSERT_LT(tile.rows, points.rows());
  ASSERT_LT(tile.columns, columns);
  const conformance::reference::Assembly expected =
      conformance::reference::assemble(points, centers, true);
  PaddedBlock output(points.rows(), columns);
  device->assemble_rbf_block(StridedPoints(points).view(), StridedPoints(centers).view(), true,
                             output.inner());
  EXPECT_TRUE(output.untouched());
  EXPECT_TRUE(conformance::expect_near(output.value(), expected.block, expected.magnitude,
                                       kEntryTolerance));
}

TEST(CudaDevice, EvaluationInChunksChangesNoBit) {
  POSEKIT_REQUIRE_CUDA();
  Random random(52);
  const RbfField field = random.field(random.points(300), 1.0, 1.0);
  const Points4 points = random.points(2003);
  Eigen::MatrixX3d whole(points.rows(), 3);
  Eigen::MatrixX3d chunked(points.rows(), 3);
  const std::unique_ptr<Device> device = make_cuda_device();
  device->evaluate_rbf(*device->upload_field(field), points, whole);
  const std::unique_ptr<Device> tiny = tiny_chunk_device();
  PaddedRows output(Eigen::MatrixX3d::Zero(points.rows(), 3));
  tiny->evaluate_rbf(*tiny->upload_field(field), StridedPoints(points).view(), output.inner());
  EXPECT_TRUE(output.untouched());
  chunked = output.value();
  EXPECT_TRUE(same_bits(whole, chunked));
  const conformance::reference::Evaluation expected = conformance::reference::evaluate(field, points);
  EXPECT_TRUE(conformance::expect_near(whole, expected.values, expected.magnitude, kSumTolerance));
}

TEST(CudaDevice, ParticlesInChunksAndThreadsThatTakeManyChangeNoBit) {
  POSEKIT_REQUIRE_CUDA();
  Random random(53);
  const RbfField field = random.field(random.ball_points(129), 0.02, 0.02);
  const Eigen::MatrixX3d start = random.ball_points(1000).leftCols<3>();
  const Rk45Options options;

  const std::unique_ptr<Device> device = make_cuda_device();
  Eigen::MatrixX3d whole = start;
  const std::vector<Rk45ParticleStats> whole_stats =
      device->integrate_rk45(*device->upload_field(field), whole, options);

  const std::unique_ptr<Device> tiny = tiny_chunk_device();  // 170 particles per chunk
  PaddedRows chunked(start);
  const std::vector<Rk45ParticleStats> chunked_stats =
      tiny->integrate_rk45(*tiny->upload_field(field), chunked.inner(), options);
  EXPECT_TRUE(chunked.untouched());
  EXPECT_TRUE(same_bits(whole, chunked.value()));
  EXPECT_TRUE(same_stats(whole_stats, chunked_stats));

  // One block of one warp for 1,000 particles: each thread takes one particle after another.
  CudaDeviceOptions one_block;
  one_block.rk45_blocks = 1;
  const std::unique_ptr<Device> single = make_cuda_device(one_block);
  Eigen::MatrixX3d taken = start;
  const std::vector<Rk45ParticleStats> taken_stats =
      single->integrate_rk45(*single->upload_field(field), taken, options);
  EXPECT_TRUE(same_bits(whole, taken));
  EXPECT_TRUE(same_stats(whole_stats, taken_stats));

  const conformance::reference::Integration expected =
      conformance::reference::integrate(field, start, options);
  const conformance::Tolerance tolerance{100 * options.absolute_tolerance,
                                         100 * options.relative_tolerance};
  EXPECT_TRUE(conformance::expect_near(whole, expected.positions, Eigen::MatrixXd(), tolerance));
  EXPECT_EQ(summarize(whole_stats).failures, 0);
}

TEST(CudaDevice, ConstraintsOfAPoseAgainstItsFieldMatchTheCpuBackend) {
  POSEKIT_REQUIRE_CUDA();
  // The sizes of the fitting-error scan on lion-01: 65,000 constraints, 2,700 centers.
  Random random(54);
  const RbfField field = random.field(random.ball_points(2700), 0.01, 0.01);
  const Points4 points = random.ball_points(65000);
  const std::unique_ptr<Device> gpu = make_cuda_device();
  const std::unique_ptr<Device> cpu = make_cpu_device();
  Eigen::MatrixX3d on_gpu(points.rows(), 3);
  Eigen::MatrixX3d on_cpu(points.rows(), 3);
  gpu->evaluate_rbf(*gpu->upload_field(field), points, on_gpu);
  cpu->evaluate_rbf(*cpu->upload_field(field), points, on_cpu);
  const double scale = on_cpu.cwiseAbs().maxCoeff();
  EXPECT_LE((on_gpu - on_cpu).cwiseAbs().maxCoeff(), 1e-12 * scale);

  Eigen::MatrixXd block_gpu(points.rows(), 128 + kRbfPolynomialTerms);
  Eigen::MatrixXd block_cpu(points.rows(), 128 + kRbfPolynomialTerms);
  const Points4 centers = field.centers.topRows(128);
  gpu->assemble_rbf_block(points, centers, true, block_gpu);
  cpu->assemble_rbf_block(points, centers, true, block_cpu);
  EXPECT_LE((block_gpu - block_cpu).cwiseAbs().maxCoeff(), 1e-13 * block_cpu.cwiseAbs().maxCoeff());
}

TEST(CudaDevice, RejectsOptionsOutOfRange) {
  CudaDeviceOptions negative;
  negative.rk45_blocks = -1;
  EXPECT_THROW(make_cuda_device(negative), ArgumentError);
}

}  // namespace
}  // namespace posekit::cuda
