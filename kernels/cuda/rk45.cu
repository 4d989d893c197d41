// posekit CUDA: batched adaptive RK45, one particle per thread, each with its own Dormand-Prince
// 5(4) steps (rk45_particle.cuh, the decisions of kernel_math.h's PK_RK45_INTEGRATE_PARTICLE), the
// field evaluated inside the thread with the block staging the centers through shared memory
// (rbf_field.cuh). Host side: backends/cuda/rk45.cpp.
//
// Every pass of the block's loop is one field evaluation per thread, at whatever stage its particle
// is. The block loops while any of its threads has a particle; a thread whose particle is done
// writes it out and takes the next one from a counter shared by the grid, so that threads do not
// idle while others finish long particles. Threads without a particle still load their share of
// every tile and take every barrier.
#include "rbf_field.cuh"
#include "rk45_particle.cuh"

#include <cstddef>

namespace posekit::cuda {
namespace {

__device__ inline void write_result(const Particles& particles, int index, const Rk45Particle& p) {
  const std::size_t stride = static_cast<std::size_t>(particles.stride);
  for (int c = 0; c < 3; ++c) particles.positions[c * stride + index] = p.x[c];
  const pk_rk45_controller& c = p.controller;
  reinterpret_cast<int4*>(particles.statistics)[index] =
      make_int4(c.accepted_steps, c.rejected_steps, c.rhs_evaluations, c.status);
}

// Starts particle `index` and, while the ones it gets need no integrating (t_end == t_begin; they
// are written at once), those after it from the counter. Returns the particle now in the thread's
// hands, or a value >= particles.count when none is left.
__device__ inline int take_particle(const Particles& particles, const Rk45Controls& controls,
                                    int index, Rk45Particle& p) {
  const std::size_t stride = static_cast<std::size_t>(particles.stride);
  const int threads = static_cast<int>(gridDim.x) * kRk45Block;
  while (index < particles.count) {
    double start[3];
    for (int c = 0; c < 3; ++c) start[c] = particles.positions[c * stride + index];
    if (rk45_start(p, start, controls.t_begin, controls.t_end, controls.relative_tolerance,
                   controls.absolute_tolerance, controls.initial_step, controls.min_step,
                   controls.max_steps)) {
      return index;
    }
    write_result(particles, index, p);
    index = threads + atomicAdd(particles.next_particle, 1);
  }
  return index;
}

__global__ void __launch_bounds__(kRk45Block)
    rk45_kernel(FieldView field, Particles particles, Rk45Controls controls) {
  __shared__ CenterTile<kRk45Tile> tile;
  __shared__ double polynomial[3 * PK_POLYNOMIAL_TERMS];
  load_polynomial(field, polynomial);
  __syncthreads();
  const int threads = static_cast<int>(gridDim.x) * kRk45Block;
  Rk45Particle p;
  int index = take_particle(particles, controls,
                            static_cast<int>(blockIdx.x) * kRk45Block + static_cast<int>(threadIdx.x),
                            p);
  bool active = index < particles.count;
  // The condition is the same in every thread of the block, so each of them reaches every barrier
  // inside (block_field_value's).
  while (__syncthreads_or(active)) {
    double point[4] = {0.0, 0.0, 0.0, 0.0};
    if (active) rk45_evaluation_point(p, point);
    double value[3];
    block_field_value(field, tile, polynomial, active, point, value);
    if (!active) continue;
    rk45_consume_evaluation(p, value);
    if (p.controller.status != PK_RK45_RUNNING) {
      write_result(particles, index, p);
      index = take_particle(particles, controls, threads + atomicAdd(particles.next_particle, 1), p);
      active = index < particles.count;
    }
  }
}

}  // namespace

// The launchers need nvcc. Everything above also compiles as host C++: tests/unit/cuda runs the
// kernel on threads of the host (kernel_emulation.hpp) to check it where there is no GPU.
#if defined(__CUDACC__)

cudaError_t launch_rk45(const FieldView& field, const Particles& particles,
                        const Rk45Controls& controls, int blocks, cudaStream_t stream) {
  if (particles.count <= 0 || blocks <= 0) return cudaSuccess;
  rk45_kernel<<<static_cast<unsigned>(blocks), kRk45Block, 0, stream>>>(field, particles, controls);
  return cudaGetLastError();
}

cudaError_t rk45_blocks_per_multiprocessor(int* blocks) {
  return cudaOccupancyMaxActiveBlocksPerMultiprocessor(blocks, rk45_kernel, kRk45Block, 0);
}

cudaError_t rk45_attributes(cudaFuncAttributes* attributes) {
  return cudaFuncGetAttributes(attributes, rk45_kernel);
}

#endif  // __CUDACC__

}  // namespace posekit::cuda
