// posekit CUDA: one tile of an RBF block, A(i, j) = phi(|y_i - c_j|) for center columns and the
// polynomial terms pi_k(y_i) for the 15 columns after them. Host side: backends/cuda/rbf_assembly.cpp.
//
// A block of kAssemblyRows x kAssemblyColumnThreads threads covers kAssemblyRows rows by
// kAssemblyColumns columns: its centers are staged in shared memory, each thread keeps its point in
// registers and walks every kAssemblyColumnThreads-th column. A warp holds 32 consecutive rows of
// one column, so each of its stores writes 256 contiguous bytes of the column-major tile.
#include "cuda/cuda_kernels.hpp"

#include "common/kernel_math.h"

#include <cstddef>

namespace posekit::cuda {
namespace {

constexpr int kAssemblyColumnThreads = 4;
constexpr int kAssemblyThreads = kAssemblyRows * kAssemblyColumnThreads;
static_assert(kAssemblyRows % 32 == 0, "a warp must lie within one column");
static_assert(kAssemblyThreads >= 4 * kAssemblyColumns, "one load per center coordinate");

// Term k (0..14) of pk_polynomial_basis.
__device__ inline double polynomial_term(int k, double x, double y, double z, double t) {
  double basis[PK_POLYNOMIAL_TERMS];
  pk_polynomial_basis(x, y, z, t, basis);
  return basis[k];
}

__global__ void __launch_bounds__(kAssemblyThreads) rbf_assemble_kernel(AssemblyTile tile) {
  __shared__ double centers[4][kAssemblyColumns];
  const int first = static_cast<int>(blockIdx.y) * kAssemblyColumns;  // first column of the block
  const int thread = static_cast<int>(threadIdx.y) * kAssemblyRows + static_cast<int>(threadIdx.x);
  if (thread < 4 * kAssemblyColumns) {
    const int coordinate = thread / kAssemblyColumns;
    const int column = first + thread % kAssemblyColumns;
    if (column < tile.columns && tile.first_column + column < tile.center_count) {
      centers[coordinate][thread % kAssemblyColumns] =
          __ldg(tile.centers + static_cast<std::size_t>(coordinate) * tile.center_stride + column);
    }
  }
  __syncthreads();
  const int row = static_cast<int>(blockIdx.x) * kAssemblyRows + static_cast<int>(threadIdx.x);
  if (row >= tile.points.count) return;
  const std::size_t point_stride = static_cast<std::size_t>(tile.points.stride);
  const double x = __ldg(tile.points.columns + row);
  const double y = __ldg(tile.points.columns + point_stride + row);
  const double z = __ldg(tile.points.columns + 2 * point_stride + row);
  const double t = __ldg(tile.points.columns + 3 * point_stride + row);
  for (int c = static_cast<int>(threadIdx.y); c < kAssemblyColumns; c += kAssemblyColumnThreads) {
    const int column = first + c;
    if (column >= tile.columns) break;
    const int block_column = tile.first_column + column;
    double value;
    if (block_column < tile.center_count) {
      value = pk_phi_from_squared_distance(pk_squared_distance(
          x - centers[0][c], y - centers[1][c], z - centers[2][c], t - centers[3][c]));
    } else {
      value = polynomial_term(block_column - tile.center_count, x, y, z, t);
    }
    tile.tile[static_cast<std::size_t>(column) * static_cast<std::size_t>(tile.tile_stride) + row] =
        value;
  }
}

// Blocks over rows by groups of kAssemblyColumns columns; the columns' y extent fits the grid
// (tile.columns <= kMaxGridY * kAssemblyColumns, checked by the launcher).
inline dim3 rbf_assemble_grid(const AssemblyTile& tile) {
  return dim3(static_cast<unsigned>((tile.points.count + kAssemblyRows - 1) / kAssemblyRows),
              static_cast<unsigned>((tile.columns + kAssemblyColumns - 1) / kAssemblyColumns));
}
const dim3 kAssemblyBlock(kAssemblyRows, kAssemblyColumnThreads);

}  // namespace

// The launchers need nvcc. Everything above also compiles as host C++: tests/unit/cuda runs the
// kernel on threads of the host (kernel_emulation.hpp) to check it where there is no GPU.
#if defined(__CUDACC__)

cudaError_t launch_rbf_assemble(const AssemblyTile& tile, cudaStream_t stream) {
  if (tile.points.count <= 0 || tile.columns <= 0) return cudaSuccess;
  const dim3 grid = rbf_assemble_grid(tile);
  if (grid.y > static_cast<unsigned>(kMaxGridY)) return cudaErrorInvalidConfiguration;
  rbf_assemble_kernel<<<grid, kAssemblyBlock, 0, stream>>>(tile);
  return cudaGetLastError();
}

cudaError_t rbf_assemble_attributes(cudaFuncAttributes* attributes) {
  return cudaFuncGetAttributes(attributes, rbf_assemble_kernel);
}

#endif  // __CUDACC__

}  // namespace posekit::cuda
