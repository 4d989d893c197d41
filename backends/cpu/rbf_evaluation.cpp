// RBF evaluation on the CPU: f(y_i) = sum_j w_j phi(|y_i - c_j|) + pi(y_i) for a batch of points.
// Threads take blocks of points; within a point, the loop over centers runs in vector lanes.
#include "cpu_operations.hpp"
#include "rbf_kernels.hpp"

#include "common/kernel_math.h"
#include <posekit/error.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>

namespace posekit::cpu {
namespace {

// The sum over centers. `omp simd reduction` permits summing in vector lanes (a reordering that the
// compiler may not do on its own without -ffast-math); -fopenmp-simd enables the pragma without
// linking an OpenMP runtime. pk_phi_from_squared_distance has no branch and no library call, so the
// whole body vectorizes.
POSEKIT_CPU_ALWAYS_INLINE void rbf_sum(const double* __restrict cx, const double* __restrict cy,
                                       const double* __restrict cz, const double* __restrict ct,
                                       const double* __restrict wx, const double* __restrict wy,
                                       const double* __restrict wz, std::ptrdiff_t count,
                                       const double* point, double* sum) {
  const double px = point[0];
  const double py = point[1];
  const double pz = point[2];
  const double pt = point[3];
  double sx = 0.0;
  double sy = 0.0;
  double sz = 0.0;
#pragma omp simd reduction(+ : sx, sy, sz)
  for (std::ptrdiff_t j = 0; j < count; ++j) {
    const double phi = pk_phi_from_squared_distance(
        pk_squared_distance(px - cx[j], py - cy[j], pz - cz[j], pt - ct[j]));
    sx += phi * wx[j];
    sy += phi * wy[j];
    sz += phi * wz[j];
  }
  sum[0] = sx;
  sum[1] = sy;
  sum[2] = sz;
}

#define POSEKIT_RBF_SUM_BODY                                                                  \
  rbf_sum(centers.x, centers.y, centers.z, centers.t, weights.x, weights.y, weights.z, count, \
          point, sum)

void rbf_sum_baseline(const Columns4& centers, const Columns3& weights, std::ptrdiff_t count,
                      const double* point, double* sum) {
  POSEKIT_RBF_SUM_BODY;
}

#if POSEKIT_CPU_MULTIVERSION
POSEKIT_CPU_TARGET_AVX2 void rbf_sum_avx2(const Columns4& centers, const Columns3& weights,
                                          std::ptrdiff_t count, const double* point, double* sum) {
  POSEKIT_RBF_SUM_BODY;
}

POSEKIT_CPU_TARGET_AVX512 void rbf_sum_avx512(const Columns4& centers, const Columns3& weights,
                                              std::ptrdiff_t count, const double* point,
                                              double* sum) {
  POSEKIT_RBF_SUM_BODY;
}
#endif

// Points per task: enough kernel evaluations (~64k) that scheduling costs nothing.
constexpr Eigen::Index kEvaluationsPerTask = 1 << 16;

}  // namespace

RbfSumKernel rbf_sum_kernel(KernelIsa isa) {
#if POSEKIT_CPU_MULTIVERSION
  if (isa == KernelIsa::avx512) return rbf_sum_avx512;
  if (isa == KernelIsa::avx2) return rbf_sum_avx2;
#else
  (void)isa;
#endif
  return rbf_sum_baseline;
}

void evaluate_rbf(const CpuExecution& execution, const CpuField& field,
                  const Eigen::Ref<const Points4>& points, Eigen::Ref<Eigen::MatrixX3d> values) {
  const Eigen::Index count = points.rows();
  const RbfSumKernel kernel = rbf_sum_kernel(execution.isa);
  const Eigen::Index grain = std::max<Eigen::Index>(
      1, kEvaluationsPerTask / std::max<Eigen::Index>(1, field.center_count()));
  execution.arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<Eigen::Index>(0, count, grain),
        [&](const tbb::blocked_range<Eigen::Index>& range) {
          for (Eigen::Index i = range.begin(); i < range.end(); ++i) {
            const double point[4] = {points(i, 0), points(i, 1), points(i, 2), points(i, 3)};
            double value[3];
            field.value_at(kernel, point, value);
            values(i, 0) = value[0];
            values(i, 1) = value[1];
            values(i, 2) = value[2];
          }
        });
  });
}

}  // namespace posekit::cpu
