// posekit CUDA: field values at a batch of points, one thread per point, the centers staged through
// shared memory by the block (rbf_field.cuh). Host side: backends/cuda/rbf_evaluation.cpp.
#include "rbf_field.cuh"

namespace posekit::cuda {
namespace {

// Points and values are columns of points.stride doubles; threads past the batch help load the
// tiles and write nothing.
__global__ void __launch_bounds__(kEvaluateBlock)
    rbf_evaluate_kernel(FieldView field, PointsView points, double* __restrict__ values) {
  __shared__ CenterTile<kEvaluateTile> tile;
  __shared__ double polynomial[3 * PK_POLYNOMIAL_TERMS];
  const int i = static_cast<int>(blockIdx.x) * kEvaluateBlock + static_cast<int>(threadIdx.x);
  const bool active = i < points.count;
  const std::size_t stride = static_cast<std::size_t>(points.stride);
  double point[4] = {0.0, 0.0, 0.0, 0.0};
  if (active) {
    for (int c = 0; c < 4; ++c) point[c] = __ldg(points.columns + c * stride + i);
  }
  load_polynomial(field, polynomial);
  __syncthreads();
  double value[3];
  block_field_value(field, tile, polynomial, active, point, value);
  if (!active) return;
  for (int c = 0; c < 3; ++c) values[c * stride + i] = value[c];
}

// One thread per point.
inline dim3 rbf_evaluate_grid(const PointsView& points) {
  return dim3(static_cast<unsigned>((points.count + kEvaluateBlock - 1) / kEvaluateBlock));
}

}  // namespace

// The launchers need nvcc. Everything above also compiles as host C++: tests/unit/cuda runs the
// kernel on threads of the host (kernel_emulation.hpp) to check it where there is no GPU.
#if defined(__CUDACC__)

cudaError_t launch_rbf_evaluate(const FieldView& field, const PointsView& points, double* values,
                                cudaStream_t stream) {
  if (points.count <= 0) return cudaSuccess;
  rbf_evaluate_kernel<<<rbf_evaluate_grid(points), kEvaluateBlock, 0, stream>>>(field, points,
                                                                                  values);
  return cudaGetLastError();
}

cudaError_t rbf_evaluate_attributes(cudaFuncAttributes* attributes) {
  return cudaFuncGetAttributes(attributes, rbf_evaluate_kernel);
}

#endif  // __CUDACC__

}  // namespace posekit::cuda
