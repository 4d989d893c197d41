#include "cuda_context.hpp"

#include "cuda_check.hpp"

#include <limits>

namespace posekit::cuda {
namespace {

const char* scratch_name(Scratch kind) {
  switch (kind) {
    case Scratch::points: return "points";
    case Scratch::centers: return "centers";
    case Scratch::tile: return "assembly tile";
    case Scratch::values: return "values";
    case Scratch::positions: return "positions";
    case Scratch::statistics: return "statistics";
    case Scratch::counter: return "particle counter";
  }
  return "scratch";
}

// cudaMemcpy2D takes pitches up to cudaDevAttrMaxPitch, 2^31 - 1 bytes on current GPUs.
constexpr Eigen::Index kMaxPitchDoubles =
    std::numeric_limits<int>::max() / static_cast<Eigen::Index>(sizeof(double));

}  // namespace

DeviceBuffer& CudaContext::scratch_buffer(Scratch kind, std::size_t bytes) {
  DeviceBuffer& buffer = scratch[static_cast<std::size_t>(kind)];
  buffer.reserve(bytes, scratch_name(kind));
  return buffer;
}

void CudaContext::make_current() const { POSEKIT_CUDA_CHECK(cudaSetDevice(ordinal)); }

void CudaContext::synchronize() const { POSEKIT_CUDA_CHECK(cudaStreamSynchronize(stream)); }

void copy_columns(const CudaContext& context, double* target, Eigen::Index target_stride,
                  const double* source, Eigen::Index source_stride, Eigen::Index rows,
                  Eigen::Index columns, cudaMemcpyKind kind) {
  if (rows <= 0 || columns <= 0) return;
  const std::size_t width = static_cast<std::size_t>(rows) * sizeof(double);
  if (target_stride == rows && source_stride == rows) {
    // Both sides contiguous (a tile with every row of an unpadded block): one plain copy.
    POSEKIT_CUDA_CHECK(cudaMemcpyAsync(target, source, width * static_cast<std::size_t>(columns),
                                       kind, context.stream));
    return;
  }
  if (columns > 1 && target_stride <= kMaxPitchDoubles && source_stride <= kMaxPitchDoubles) {
    POSEKIT_CUDA_CHECK(cudaMemcpy2DAsync(
        target, static_cast<std::size_t>(target_stride) * sizeof(double), source,
        static_cast<std::size_t>(source_stride) * sizeof(double), width,
        static_cast<std::size_t>(columns), kind, context.stream));
    return;
  }
  for (Eigen::Index c = 0; c < columns; ++c) {
    POSEKIT_CUDA_CHECK(cudaMemcpyAsync(target + c * target_stride, source + c * source_stride,
                                       width, kind, context.stream));
  }
}

}  // namespace posekit::cuda
