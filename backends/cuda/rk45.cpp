// RK45 batch integration on a CUDA device: one launch per chunk of particles (one chunk unless the
// particles outgrow the scratch budget), in which every thread runs its particle's whole adaptive
// Dormand-Prince loop and then takes the next particle (kernels/cuda/rk45.cu). The grid is as
// large as the GPU holds at once, or smaller for a small batch.
#include "chunking.hpp"
#include "cuda_check.hpp"
#include "cuda_kernels.hpp"
#include "cuda_operations.hpp"

#include "common/rk45_counters.hpp"

#include <algorithm>
#include <cstdint>

namespace posekit::cuda {

std::vector<Rk45ParticleStats> integrate_rk45(CudaContext& context, const CudaField& field,
                                              Eigen::Ref<Eigen::MatrixX3d> positions,
                                              const Rk45Options& options) {
  const Eigen::Index count = positions.rows();
  std::vector<Rk45ParticleStats> stats(static_cast<std::size_t>(count));
  // Positions (three doubles per particle) make the larger of the two buffers.
  const Eigen::Index capacity =
      std::min(count, items_per_chunk(chunk_limits(context.max_chunk_bytes), 3 * sizeof(double)));
  double* const position_buffer =
      context.scratch_buffer(Scratch::positions, 3 * sizeof(double) * capacity).as<double>();
  int* const statistics_buffer =
      context.scratch_buffer(Scratch::statistics, 4 * sizeof(int) * capacity).as<int>();
  int* const counter = context.scratch_buffer(Scratch::counter, sizeof(int)).as<int>();
  std::vector<std::int32_t> chunk_stats(static_cast<std::size_t>(4 * capacity));

  Rk45Controls controls;
  controls.t_begin = options.t_begin;
  controls.t_end = options.t_end;
  controls.relative_tolerance = options.relative_tolerance;
  controls.absolute_tolerance = options.absolute_tolerance;
  controls.initial_step = options.initial_step;
  controls.min_step = options.min_step;
  controls.max_steps = options.max_steps;
  const FieldView view = field.view();

  for (Eigen::Index first = 0; first < count; first += capacity) {
    const Eigen::Index rows = std::min(capacity, count - first);
    copy_columns(context, position_buffer, capacity, positions.data() + first,
                 positions.outerStride(), rows, 3, cudaMemcpyHostToDevice);
    POSEKIT_CUDA_CHECK(cudaMemsetAsync(counter, 0, sizeof(int), context.stream));
    Particles particles;
    particles.positions = position_buffer;
    particles.statistics = statistics_buffer;
    particles.next_particle = counter;
    particles.count = static_cast<int>(rows);
    particles.stride = static_cast<int>(capacity);
    const Eigen::Index blocks_needed = (rows + kRk45Block - 1) / kRk45Block;
    const int blocks = static_cast<int>(
        std::min<Eigen::Index>(blocks_needed, std::max(context.rk45_max_blocks, 1)));
    POSEKIT_CUDA_CHECK(launch_rk45(view, particles, controls, blocks, context.stream));
    POSEKIT_CUDA_CHECK(cudaMemcpyAsync(chunk_stats.data(), statistics_buffer,
                                       4 * sizeof(int) * static_cast<std::size_t>(rows),
                                       cudaMemcpyDeviceToHost, context.stream));
    copy_columns(context, positions.data() + first, positions.outerStride(), position_buffer,
                 capacity, rows, 3, cudaMemcpyDeviceToHost);
    context.synchronize();
    for (Eigen::Index i = 0; i < rows; ++i) {
      stats[static_cast<std::size_t>(first + i)] =
          backends::particle_stats(&chunk_stats[static_cast<std::size_t>(4 * i)]);
    }
  }
  return stats;
}

}  // namespace posekit::cuda
