// The CUDA kernels themselves, compiled as host C++ and run on host threads (kernel_emulation.hpp),
// against the formulas of kernel_math.h evaluated in the same order: every value must agree to the
// last bit (both sides are compiled by the same compiler without contraction), every entry outside
// the output must stay untouched. Odd sizes leave partial tiles, partial blocks and more particles
// than threads. On a GPU, nvcc contracts multiply-adds, and the conformance suite holds the real
// kernels against the reference within tolerance instead.
#include "conformance.hpp"

#include <posekit/device.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "kernel_emulation.hpp"

#include "cuda/rbf_assembly.cu"
#include "cuda/rbf_evaluate.cu"
#include "cuda/rk45.cu"

namespace posekit::cuda {
namespace {

constexpr double kUntouched = -1.2345678901234567e300;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A field in FieldView's layout, with its value summed as the kernels sum it.
struct ColumnField {
  int count = 0;
  std::vector<double> data;  // 7 columns of count doubles, then the 45 coefficients

  explicit ColumnField(const RbfField& field) : count(static_cast<int>(field.centers.rows())) {
    data.resize(7 * static_cast<std::size_t>(count) + 3 * kRbfPolynomialTerms);
    for (int j = 0; j < count; ++j) {
      for (int c = 0; c < 4; ++c) data[c * count + j] = field.centers(j, c);
      for (int c = 0; c < 3; ++c) data[(4 + c) * count + j] = field.weights(j, c);
    }
    std::copy(field.polynomial.data(), field.polynomial.data() + 3 * kRbfPolynomialTerms,
              data.begin() + 7 * count);
  }
  FieldView view() const {
    return FieldView{data.data(), data.data() + 7 * count, count};
  }
  void value(const double* p, double* value) const {
    double sum[3] = {0.0, 0.0, 0.0};
    for (int j = 0; j < count; ++j) {
      const double phi = pk_phi_from_squared_distance(
          pk_squared_distance(p[0] - data[j], p[1] - data[count + j], p[2] - data[2 * count + j],
                              p[3] - data[3 * count + j]));
      for (int c = 0; c < 3; ++c) sum[c] += phi * data[(4 + c) * count + j];
    }
    for (int c = 0; c < 3; ++c) {
      value[c] = sum[c] + pk_polynomial_value(&data[7 * count + c * kRbfPolynomialTerms], p[0],
                                              p[1], p[2], p[3]);
    }
  }
};

// Points as columns of `stride` doubles, the rows past the points filled with kUntouched.
std::vector<double> point_columns(const Points4& points, int stride, int columns) {
  std::vector<double> data(static_cast<std::size_t>(stride) * columns, kUntouched);
  for (int c = 0; c < columns; ++c) {
    for (Eigen::Index i = 0; i < points.rows(); ++i) data[c * stride + i] = points(i, c);
  }
  return data;
}

void expect_evaluation(int points, int centers, std::uint64_t seed) {
  SCOPED_TRACE(std::to_string(points) + " points, " + std::to_string(centers) + " centers");
  conformance::Random random(seed);
  const ColumnField field(random.field(random.points(centers), 1.0, 1.0));
  const int stride = points + 3;
  const std::vector<double> input = point_columns(random.points(points), stride, 4);
  std::vector<double> values(3 * static_cast<std::size_t>(stride), kUntouched);
  const PointsView view{input.data(), points, stride};
  emulation::launch(rbf_evaluate_kernel, rbf_evaluate_grid(view), dim3(kEvaluateBlock),
                    field.view(), view, values.data());
  int mismatches = 0;
  for (int i = 0; i < stride; ++i) {
    double expected[3] = {kUntouched, kUntouched, kUntouched};
    if (i < points) {
      const double p[4] = {input[i], input[stride + i], input[2 * stride + i],
                           input[3 * stride + i]};
      field.value(p, expected);
    }
    for (int c = 0; c < 3; ++c) mismatches += !same_bits(values[c * stride + i], expected[c]);
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(CudaKernelsOnHost, EvaluationSumsEveryTileOfCenters) {
  expect_evaluation(1, 1, 61);
  expect_evaluation(5, 0, 62);         // the polynomial alone
  expect_evaluation(300, 257, 63);     // three blocks, the second tile holds one center
  expect_evaluation(129, 600, 64);     // a last tile of 88 centers
}

void expect_assembly(int rows, int centers, int first_column, int columns, std::uint64_t seed) {
  SCOPED_TRACE(std::to_string(rows) + " rows, columns " + std::to_string(first_column) + " to " +
               std::to_string(first_column + columns - 1) + " of " + std::to_string(centers) +
               " centers and 15 terms");
  conformance::Random random(seed);
  const std::vector<double> points = point_columns(random.points(rows), rows, 4);
  const int tile_centers = std::clamp(centers - first_column, 0, columns);
  const std::vector<double> center_columns = point_columns(random.points(tile_centers), columns, 4);
  const int tile_stride = rows + 2;
  std::vector<double> tile(static_cast<std::size_t>(tile_stride) * (columns + 1), kUntouched);
  AssemblyTile launch;
  launch.points = PointsView{points.data(), rows, rows};
  launch.centers = center_columns.data();
  launch.center_stride = columns;
  launch.center_count = centers;
  launch.first_column = first_column;
  launch.columns = columns;
  launch.tile = tile.data();
  launch.tile_stride = tile_stride;
  emulation::launch(rbf_assemble_kernel, rbf_assemble_grid(launch), kAssemblyBlock, launch);
  int mismatches = 0;
  for (int j = 0; j <= columns; ++j) {
    for (int i = 0; i < tile_stride; ++i) {
      double expected = kUntouched;
      if (j < columns && i < rows) {
        const double x = points[i], y = points[rows + i], z = points[2 * rows + i],
                     t = points[3 * rows + i];
        if (first_column + j < centers) {
          expected = pk_phi_from_squared_distance(pk_squared_distance(
              x - center_columns[j], y - center_columns[columns + j],
              z - center_columns[2 * columns + j], t - center_columns[3 * columns + j]));
        } else {
          double basis[PK_POLYNOMIAL_TERMS];
          pk_polynomial_basis(x, y, z, t, basis);
          expected = basis[first_column + j - centers];
        }
      }
      mismatches += !same_bits(tile[static_cast<std::size_t>(j) * tile_stride + i], expected);
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(CudaKernelsOnHost, AssemblyWritesEachEntryOfTheTileOnce) {
  expect_assembly(70, 40, 0, 55, 65);    // two row blocks, two column blocks, centers and terms
  expect_assembly(1, 3, 0, 18, 66);
  expect_assembly(130, 100, 64, 51, 67);  // a later tile: 36 centers, then the 15 terms
  expect_assembly(65, 10, 10, 15, 68);    // the terms alone
}

// Integrates `particles` particles in `blocks` blocks and compares each with the loop of
// kernel_math.h run on the same field.
void expect_integration(int particles, int centers, int blocks, const Rk45Options& options,
                        std::uint64_t seed) {
  SCOPED_TRACE(std::to_string(particles) + " particles, " + std::to_string(centers) +
               " centers, " + std::to_string(blocks) + " blocks");
  conformance::Random random(seed);
  const ColumnField field(random.field(random.ball_points(centers), 0.02, 0.02));
  const Points4 start = random.ball_points(particles);
  const int stride = particles + 5;
  std::vector<double> positions = point_columns(start, stride, 3);
  std::vector<int> statistics(4 * static_cast<std::size_t>(particles), -1);
  int counter = 0;
  Particles launch;
  launch.positions = positions.data();
  launch.statistics = statistics.data();
  launch.next_particle = &counter;
  launch.count = particles;
  launch.stride = stride;
  const Rk45Controls controls{options.t_begin,      options.t_end,
                              options.relative_tolerance, options.absolute_tolerance,
                              options.initial_step, options.min_step,
                              options.max_steps};
  emulation::launch(rk45_kernel, dim3(static_cast<unsigned>(blocks)), dim3(kRk45Block),
                    field.view(), launch, controls);
  int mismatches = 0;
  int failed_particle = -1;
  for (int i = 0; i < particles; ++i) {
    double x[3] = {start(i, 0), start(i, 1), start(i, 2)};
    pk_rk45_controller c;
    pk_rk45_begin(&c, options.t_begin, options.t_end, options.relative_tolerance,
                  options.absolute_tolerance, options.initial_step, options.min_step,
                  options.max_steps);
    const auto evaluate = [&field](const double* point, double* value) {
      field.value(point, value);
    };
    PK_RK45_INTEGRATE_PARTICLE(c, x, evaluate);
    const int* s = &statistics[4 * static_cast<std::size_t>(i)];
    bool same = s[0] == c.accepted_steps && s[1] == c.rejected_steps &&
                s[2] == c.rhs_evaluations && s[3] == c.status;
    for (int k = 0; k < 3; ++k) same = same && same_bits(positions[k * stride + i], x[k]);
    if (!same && failed_particle < 0) failed_particle = i;
    mismatches += !same;
  }
  for (int i = particles; i < stride; ++i) {
    for (int k = 0; k < 3; ++k) mismatches += !same_bits(positions[k * stride + i], kUntouched);
  }
  EXPECT_EQ(mismatches, 0) << "first differing particle " << failed_particle;
  // Every particle past the grid's first one per thread was taken from the counter once, and each
  // thread that had a particle ended with one take that found none: one count per particle.
  EXPECT_EQ(counter, particles);
}

TEST(CudaKernelsOnHost, Rk45ThreadsTakeParticleAfterParticle) {
  const Rk45Options defaults;
  expect_integration(100, 129, 1, defaults, 69);  // 32 threads for 100 particles
  expect_integration(70, 300, 3, defaults, 70);   // more threads than particles
  expect_integration(45, 5, 1, defaults, 71);
}

TEST(CudaKernelsOnHost, Rk45EndsEveryParticleAsTheLoopDoes) {
  Rk45Options zero_interval;
  zero_interval.t_begin = zero_interval.t_end = 0.5;
  expect_integration(50, 7, 1, zero_interval, 72);
  Rk45Options max_steps;
  max_steps.initial_step = 1e-3;
  max_steps.max_steps = 4;
  expect_integration(40, 7, 1, max_steps, 73);
  Rk45Options backward;
  backward.t_begin = 1.0;
  backward.t_end = 0.3;
  expect_integration(33, 20, 1, backward, 74);
}

}  // namespace
}  // namespace posekit::cuda
