// The interface between the CUDA backend's host code (backends/cuda, C++) and its kernels
// (kernels/cuda/*.cu, nvcc): plain structs of device pointers and sizes, and one launcher per
// kernel. A launcher enqueues its kernel on `stream` and returns the launch's cudaError_t; errors of
// the kernel's execution appear at the next synchronization. Included by both compilers, so it
// holds nothing but C++ that nvcc's host compiler and g++ both accept and no Eigen.
#pragma once

#include <cuda_runtime_api.h>

namespace posekit::cuda {

/// Threads per block of the evaluation kernel and centers per shared-memory tile of it.
constexpr int kEvaluateBlock = 128;
constexpr int kEvaluateTile = 256;
/// The same for the RK45 kernel: blocks of one warp, so that the few thousand particles of a pose
/// still spread over every multiprocessor (5,000 particles make 157 blocks).
constexpr int kRk45Block = 32;
constexpr int kRk45Tile = 128;
/// A block of the assembly kernel covers kAssemblyRows rows by kAssemblyColumns columns.
constexpr int kAssemblyRows = 64;
constexpr int kAssemblyColumns = 32;
/// Largest grid extent in y (CUDA's limit), which bounds the columns of one assembly launch.
constexpr int kMaxGridY = 65535;

/// A field on the device: 7 columns of `count` doubles (center x, y, z, t, weight x, y, z) at
/// `columns`, and the 15 by 3 polynomial (column-major, 45 doubles) at `polynomial`.
struct FieldView {
  const double* columns = nullptr;
  const double* polynomial = nullptr;
  int count = 0;
};

/// `count` points (x, y, z, t) as 4 columns of `stride` doubles.
struct PointsView {
  const double* columns = nullptr;
  int count = 0;
  int stride = 0;
};

/// One tile of an RBF block: block rows 0 .. rows - 1 of the tile's points by block columns
/// first_column .. first_column + columns - 1, where block column j < center_count is center j
/// and the others are the polynomial terms j - center_count. `centers` holds the tile's centers
/// (the first being block column first_column) as 4 columns of `center_stride` doubles; the tile is
/// written column-major with leading dimension `tile_stride` (>= rows).
struct AssemblyTile {
  PointsView points;
  const double* centers = nullptr;
  int center_stride = 0;
  int center_count = 0;
  int first_column = 0;
  int columns = 0;
  double* tile = nullptr;
  int tile_stride = 0;
};

/// The controls of Rk45Options, as the kernel reads them.
struct Rk45Controls {
  double t_begin = 0;
  double t_end = 0;
  double relative_tolerance = 0;
  double absolute_tolerance = 0;
  double initial_step = 0;
  double min_step = 0;
  int max_steps = 0;
};

/// `count` particles: positions as 3 columns of `stride` doubles (start in, end out), statistics
/// out as 4 ints per particle (accepted, rejected, field evaluations, status), and a counter
/// (zeroed before the launch) from which threads that are done take further particles.
struct Particles {
  double* positions = nullptr;
  int* statistics = nullptr;
  int* next_particle = nullptr;
  int count = 0;
  int stride = 0;
};

/// Values (3 columns of points.stride doubles) of `field` at `points`.
cudaError_t launch_rbf_evaluate(const FieldView& field, const PointsView& points, double* values,
                                cudaStream_t stream);

/// One tile of an RBF block (see AssemblyTile); tile.columns <= kMaxGridY * kAssemblyColumns.
cudaError_t launch_rbf_assemble(const AssemblyTile& tile, cudaStream_t stream);

/// Integrates every particle through `field` in `blocks` blocks of kRk45Block threads; threads
/// whose particle is done take the next one until none is left.
cudaError_t launch_rk45(const FieldView& field, const Particles& particles,
                        const Rk45Controls& controls, int blocks, cudaStream_t stream);

/// How many blocks of the RK45 kernel one multiprocessor holds at once (at least 1 on success).
cudaError_t rk45_blocks_per_multiprocessor(int* blocks);

/// Attributes of each kernel on the current device; cudaErrorNoKernelImageForDevice when this
/// build has no code for the device's architecture.
cudaError_t rbf_evaluate_attributes(cudaFuncAttributes* attributes);
cudaError_t rbf_assemble_attributes(cudaFuncAttributes* attributes);
cudaError_t rk45_attributes(cudaFuncAttributes* attributes);

}  // namespace posekit::cuda
