// What the three operations of a CUDA device share: the GPU's ordinal, one stream, launch shapes,
// the scratch budget and the scratch buffers.
#pragma once

#include "cuda_buffer.hpp"

#include <cuda_runtime_api.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>

namespace posekit::cuda {

/// Buffers an operation needs only while it runs, kept between calls and grown on demand
/// (cudaMalloc synchronizes the device and costs more than a small launch).
enum class Scratch { points, centers, tile, values, positions, statistics, counter };
constexpr std::size_t kScratchKinds = 7;

/// The device's state; the device's mutex guards every use.
struct CudaContext {
  int ordinal = 0;
  cudaStream_t stream = nullptr;
  std::uint64_t max_chunk_bytes = 0;  ///< no scratch buffer is larger
  int rk45_max_blocks = 1;            ///< RK45 blocks resident on the whole GPU at once
  std::uint64_t id = 0;               ///< tells fields of this device from those of others
  std::array<DeviceBuffer, kScratchKinds> scratch;

  /// Scratch buffer `kind`, at least `bytes` (> 0) long.
  DeviceBuffer& scratch_buffer(Scratch kind, std::size_t bytes);
  /// Makes the device current in the calling thread (each host thread has its own current device).
  void make_current() const;
  /// Waits for the stream; throws DeviceError with the first error of the work on it.
  void synchronize() const;
};

/// Copies `rows` rows of `columns` columns between column-major storages: from `source` (columns
/// `source_stride` doubles apart) to `target` (columns `target_stride` doubles apart), on the
/// context's stream. `kind` says which side is the device. One plain copy when both sides are
/// contiguous, one rectangular copy when the strides allow it, else one copy per column. Returns
/// once the host side may be reused (a copy from pageable host memory is staged, a copy to it
/// completes).
void copy_columns(const CudaContext& context, double* target, Eigen::Index target_stride,
                  const double* source, Eigen::Index source_stride, Eigen::Index rows,
                  Eigen::Index columns, cudaMemcpyKind kind);

}  // namespace posekit::cuda
