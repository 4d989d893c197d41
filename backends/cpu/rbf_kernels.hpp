// The CPU backend's two hot loops, one copy per instruction set (see kernel_isa.hpp).
#pragma once

#include "kernel_isa.hpp"

#include <cstddef>

namespace posekit::cpu {

/// Four contiguous coordinate columns (x, y, z, t) of a set of points: structure of arrays.
struct Columns4 {
  const double* x;
  const double* y;
  const double* z;
  const double* t;
};

/// Three contiguous columns, one per component of the field's weights.
struct Columns3 {
  const double* x;
  const double* y;
  const double* z;
};

/// sum[0..2] = sum_j weights_j phi(|point - centers_j|) over `count` centers; point is (x, y, z,
/// t).
using RbfSumKernel = void (*)(const Columns4& centers, const Columns3& weights,
                              std::ptrdiff_t count, const double* point, double* sum);

/// column[i] = phi(|points_i - center|) for the first `count` points; center is (x, y, z, t).
using PhiColumnKernel = void (*)(const Columns4& points, std::ptrdiff_t count, const double* center,
                                 double* column);

/// The copy of each loop compiled for `isa`, which must be supported (rbf_evaluation.cpp and
/// rbf_assembly.cpp).
RbfSumKernel rbf_sum_kernel(KernelIsa isa);
PhiColumnKernel phi_column_kernel(KernelIsa isa);

}  // namespace posekit::cpu
