// RBF evaluation on the CPU: f(y_i) = sum_j w_j phi(|y_i - c_j|) + pi(y_i) for a batch of points.
// Threads take blocks of points; within a point, the loop over centers runs in vector lanes.
#include "cpu_operations.hpp"
#include "rbf_kernels.hpp"

#include "common/kernel_math.h"
#include <posekit/error.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace posekit::cpu {
namespace {

// The sum over centers, in eight lanes whatever the vector width: center j goes to lane j mod 8
// for the whole blocks of eight, the last count mod 8 centers to lane 0 in order, and the lanes are
// added 0 to 7 at the end. The order is written out, not left to the vectorizer, so the copies that
// fuse multiply-adds (AVX2 in two 4-wide halves, AVX-512 in one 8-wide register) round alike and a
// correction gives the same bits on either processor; it is the order the AVX-512 copy's vectorized
// reduction had, so earlier results hold. The baseline copy has no fused multiply-add in its
// blocks and rounds differently. -fopenmp-simd lets the lane loop run in vector lanes without an
// OpenMP runtime; pk_phi_from_squared_distance has no branch and no library call, so the whole
// body vectorizes.
constexpr std::ptrdiff_t kSumLanes = 8;

POSEKIT_CPU_ALWAYS_INLINE double phi_to_center(const double* __restrict cx,
                                               const double* __restrict cy,
                                               const double* __restrict cz,
                                               const double* __restrict ct, std::ptrdiff_t j,
                                               const double* point) {
  return pk_phi_from_squared_distance(pk_squared_distance(point[0] - cx[j], point[1] - cy[j],
                                                          point[2] - cz[j], point[3] - ct[j]));
}

POSEKIT_CPU_ALWAYS_INLINE void rbf_sum(const double* __restrict cx, const double* __restrict cy,
                                       const double* __restrict cz, const double* __restrict ct,
                                       const double* __restrict wx, const double* __restrict wy,
                                       const double* __restrict wz, std::ptrdiff_t count,
                                       const double* point, double* sum) {
  double lane_x[kSumLanes] = {};
  double lane_y[kSumLanes] = {};
  double lane_z[kSumLanes] = {};
  const std::ptrdiff_t whole_blocks_end = count - count % kSumLanes;
  for (std::ptrdiff_t block = 0; block < whole_blocks_end; block += kSumLanes) {
#pragma omp simd
    for (std::ptrdiff_t lane = 0; lane < kSumLanes; ++lane) {
      const double phi = phi_to_center(cx, cy, cz, ct, block + lane, point);
      lane_x[lane] += phi * wx[block + lane];
      lane_y[lane] += phi * wy[block + lane];
      lane_z[lane] += phi * wz[block + lane];
    }
  }
  for (std::ptrdiff_t j = whole_blocks_end; j < count; ++j) {
    const double phi = phi_to_center(cx, cy, cz, ct, j, point);
    // std::fma, not a contracted +=: the vectorizer may otherwise sum this in-order reduction as
    // separate products and additions in one copy and fused ones in another.
    lane_x[0] = std::fma(phi, wx[j], lane_x[0]);
    lane_y[0] = std::fma(phi, wy[j], lane_y[0]);
    lane_z[0] = std::fma(phi, wz[j], lane_z[0]);
  }
  double sx = 0.0;
  double sy = 0.0;
  double sz = 0.0;
  for (std::ptrdiff_t lane = 0; lane < kSumLanes; ++lane) {
    sx += lane_x[lane];
    sy += lane_y[lane];
    sz += lane_z[lane];
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
