// RBF assembly on the CPU: the block A(i, j) = phi(|y_i - c_j|) plus the 15 polynomial columns.
// Column-major output, so each center's column is a contiguous run over points: the inner loop
// writes it with unit stride in vector lanes. Threads take rectangles of rows by columns.
#include "cpu_operations.hpp"
#include "rbf_kernels.hpp"

#include "common/kernel_math.h"
#include <posekit/error.hpp>

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <string>

namespace posekit::cpu {
namespace {

// No reduction here; the pragma only tells the compiler the iterations are independent.
POSEKIT_CPU_ALWAYS_INLINE void phi_column(const double* __restrict px, const double* __restrict py,
                                          const double* __restrict pz, const double* __restrict pt,
                                          std::ptrdiff_t count, const double* center,
                                          double* __restrict column) {
  const double cx = center[0];
  const double cy = center[1];
  const double cz = center[2];
  const double ct = center[3];
#pragma omp simd
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    column[i] = pk_phi_from_squared_distance(
        pk_squared_distance(px[i] - cx, py[i] - cy, pz[i] - cz, pt[i] - ct));
  }
}

#define POSEKIT_PHI_COLUMN_BODY \
  phi_column(points.x, points.y, points.z, points.t, count, center, column)

void phi_column_baseline(const Columns4& points, std::ptrdiff_t count, const double* center,
                         double* column) {
  POSEKIT_PHI_COLUMN_BODY;
}

#if POSEKIT_CPU_MULTIVERSION
POSEKIT_CPU_TARGET_AVX2 void phi_column_avx2(const Columns4& points, std::ptrdiff_t count,
                                             const double* center, double* column) {
  POSEKIT_PHI_COLUMN_BODY;
}

POSEKIT_CPU_TARGET_AVX512 void phi_column_avx512(const Columns4& points, std::ptrdiff_t count,
                                                 const double* center, double* column) {
  POSEKIT_PHI_COLUMN_BODY;
}
#endif

// A task covers at least kRowGrain x kColumnGrain entries (16k kernel evaluations).
constexpr Eigen::Index kRowGrain = 1024;
constexpr Eigen::Index kColumnGrain = 16;

Columns4 rows_from(const Eigen::Ref<const Points4>& points, Eigen::Index first_row) {
  return {points.col(0).data() + first_row, points.col(1).data() + first_row,
          points.col(2).data() + first_row, points.col(3).data() + first_row};
}

}  // namespace

PhiColumnKernel phi_column_kernel(KernelIsa isa) {
#if POSEKIT_CPU_MULTIVERSION
  if (isa == KernelIsa::avx512) return phi_column_avx512;
  if (isa == KernelIsa::avx2) return phi_column_avx2;
#else
  (void)isa;
#endif
  return phi_column_baseline;
}

void assemble_rbf_block(const CpuExecution& execution, const Eigen::Ref<const Points4>& points,
                        const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                        Eigen::Ref<Eigen::MatrixXd> block) {
  const Eigen::Index rows = points.rows();
  const Eigen::Index center_count = centers.rows();
  const PhiColumnKernel kernel = phi_column_kernel(execution.isa);
  execution.arena.execute([&] {
    if (center_count > 0) {
      tbb::parallel_for(
          tbb::blocked_range2d<Eigen::Index>(0, rows, kRowGrain, 0, center_count, kColumnGrain),
          [&](const tbb::blocked_range2d<Eigen::Index>& range) {
            const Eigen::Index first_row = range.rows().begin();
            const Columns4 point_columns = rows_from(points, first_row);
            for (Eigen::Index j = range.cols().begin(); j < range.cols().end(); ++j) {
              const double center[4] = {centers(j, 0), centers(j, 1), centers(j, 2), centers(j, 3)};
              kernel(point_columns, static_cast<std::ptrdiff_t>(range.rows().size()), center,
                     block.col(j).data() + first_row);
            }
          });
    }
    if (with_polynomial) {
      tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, rows, kRowGrain),
                        [&](const tbb::blocked_range<Eigen::Index>& range) {
                          double basis[PK_POLYNOMIAL_TERMS];
                          for (Eigen::Index i = range.begin(); i < range.end(); ++i) {
                            pk_polynomial_basis(points(i, 0), points(i, 1), points(i, 2),
                                                points(i, 3), basis);
                            for (int k = 0; k < PK_POLYNOMIAL_TERMS; ++k) {
                              block(i, center_count + k) = basis[k];
                            }
                          }
                        });
    }
  });
}

}  // namespace posekit::cpu
