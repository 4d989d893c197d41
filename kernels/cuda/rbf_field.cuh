// posekit CUDA: the value of an uploaded field at one point per thread, the block's threads staging
// the centers through shared memory tile by tile. Shared by the evaluation and the RK45 kernels.
//
// Mirrors CpuField::value_at (backends/cpu/cpu_field.cpp): the sum over centers in the order of j
// (one accumulator per component), then each component's polynomial value (pk_polynomial_value of
// kernel_math.h) added to it.
#pragma once

#include "cuda/cuda_kernels.hpp"

#include "common/kernel_math.h"

namespace posekit::cuda {

/// kTile centers in shared memory, paired so that one thread reads a center with four 16-byte
/// loads; every thread of a warp reads the same center at once (a broadcast).
template <int kTile>
struct CenterTile {
  double2 xy[kTile];
  double2 zt[kTile];
  double2 weight_xy[kTile];
  double weight_z[kTile];
};

/// Copies the 45 polynomial coefficients into shared memory; the caller synchronizes before use.
__device__ inline void load_polynomial(const FieldView& field, double* polynomial) {
  for (int k = static_cast<int>(threadIdx.x); k < 3 * PK_POLYNOMIAL_TERMS;
       k += static_cast<int>(blockDim.x)) {
    polynomial[k] = field.polynomial[k];
  }
}

/// value[0..2] = f(point) for the threads with `active` set. Contains barriers: every thread of the
/// (one-dimensional) block calls it, active or not, with the same field. Threads that are not active
/// still load their share of each tile, so that the block keeps cooperating while some of its
/// threads have nothing to evaluate; they skip the arithmetic and leave `value` unset.
template <int kTile>
__device__ inline void block_field_value(const FieldView& field, CenterTile<kTile>& tile,
                                         const double* polynomial, bool active,
                                         const double* point, double* value) {
  const double* __restrict__ cx = field.columns;
  const double* __restrict__ cy = cx + field.count;
  const double* __restrict__ cz = cy + field.count;
  const double* __restrict__ ct = cz + field.count;
  const double* __restrict__ wx = ct + field.count;
  const double* __restrict__ wy = wx + field.count;
  const double* __restrict__ wz = wy + field.count;
  const double px = point[0];
  const double py = point[1];
  const double pz = point[2];
  const double pt = point[3];
  double sx = 0.0;
  double sy = 0.0;
  double sz = 0.0;
  for (int base = 0; base < field.count; base += kTile) {
    const int in_tile = field.count - base < kTile ? field.count - base : kTile;
    // Consecutive threads read consecutive centers of each column: coalesced.
    for (int k = static_cast<int>(threadIdx.x); k < in_tile; k += static_cast<int>(blockDim.x)) {
      const int j = base + k;
      tile.xy[k] = make_double2(__ldg(cx + j), __ldg(cy + j));
      tile.zt[k] = make_double2(__ldg(cz + j), __ldg(ct + j));
      tile.weight_xy[k] = make_double2(__ldg(wx + j), __ldg(wy + j));
      tile.weight_z[k] = __ldg(wz + j);
    }
    __syncthreads();
    if (active) {
      // Unrolled for independent logarithms in flight; the sums still run in the order of j.
#if defined(__CUDA_ARCH__)
#pragma unroll 4
#endif
      for (int k = 0; k < in_tile; ++k) {
        const double2 xy = tile.xy[k];
        const double2 zt = tile.zt[k];
        const double phi = pk_phi_from_squared_distance(
            pk_squared_distance(px - xy.x, py - xy.y, pz - zt.x, pt - zt.y));
        const double2 weight_xy = tile.weight_xy[k];
        sx += phi * weight_xy.x;
        sy += phi * weight_xy.y;
        sz += phi * tile.weight_z[k];
      }
    }
    // The next tile overwrites this one.
    __syncthreads();
  }
  if (!active) return;
  value[0] = sx + pk_polynomial_value(polynomial, px, py, pz, pt);
  value[1] = sy + pk_polynomial_value(polynomial + PK_POLYNOMIAL_TERMS, px, py, pz, pt);
  value[2] = sz + pk_polynomial_value(polynomial + 2 * PK_POLYNOMIAL_TERMS, px, py, pz, pt);
}

}  // namespace posekit::cuda
