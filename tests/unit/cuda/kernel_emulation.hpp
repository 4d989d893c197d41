// Runs the CUDA backend's kernels (kernels/cuda/*.cu, compiled here as host C++) on threads of the
// host: every block of a grid in turn, each of its threads an std::thread, __syncthreads a barrier
// of the block's threads, shared memory the kernel's static variables (one block at a time uses
// them). Slow and only for small grids, but it executes the kernels' own index arithmetic, tile
// loops, barriers and particle counter on a machine without a GPU: a thread that skipped a barrier
// would hang or corrupt a tile, an index off by one would change a result.
//
// Include this header before a kernel's .cu file; the .cu files leave their launchers (nvcc only)
// out of a host compilation.
#pragma once

#include <cuda_runtime_api.h>
#include <vector_functions.h>

#include <pthread.h>

#include <atomic>
#include <thread>
#include <vector>

// The CUDA keywords the kernels use, for a host compiler (cuda_runtime_api.h defines some of them
// for host code already, as attributes that do not apply here).
#undef __global__
#undef __device__
#undef __shared__
#undef __launch_bounds__
#define __global__
#define __device__
#define __shared__ static
#define __launch_bounds__(threads)

namespace posekit::cuda::emulation {

/// The block that runs now: its barrier and the flag of __syncthreads_or.
struct BlockState {
  pthread_barrier_t barrier;
  std::atomic<int> any{0};
};
inline BlockState* current_block = nullptr;

}  // namespace posekit::cuda::emulation

inline thread_local uint3 threadIdx;
inline thread_local uint3 blockIdx;
inline dim3 blockDim;
inline dim3 gridDim;

inline void __syncthreads() { pthread_barrier_wait(&posekit::cuda::emulation::current_block->barrier); }

inline int __syncthreads_or(int predicate) {
  posekit::cuda::emulation::BlockState& block = *posekit::cuda::emulation::current_block;
  __syncthreads();  // every thread has read the previous result
  if (threadIdx.x == 0 && threadIdx.y == 0) block.any = 0;
  __syncthreads();
  if (predicate) block.any = 1;
  __syncthreads();
  return block.any.load();
}

template <typename T>
T __ldg(const T* address) {
  return *address;
}

inline int atomicAdd(int* address, int value) {
  return __atomic_fetch_add(address, value, __ATOMIC_SEQ_CST);
}

namespace posekit::cuda::emulation {

/// kernel<<<grid, block>>>(arguments...), run to completion on the host.
template <typename Kernel, typename... Arguments>
void launch(Kernel kernel, dim3 grid, dim3 block, Arguments... arguments) {
  gridDim = grid;
  blockDim = block;
  const unsigned threads = block.x * block.y * block.z;
  for (unsigned by = 0; by < grid.y; ++by) {
    for (unsigned bx = 0; bx < grid.x; ++bx) {
      BlockState state;
      pthread_barrier_init(&state.barrier, nullptr, threads);
      current_block = &state;
      std::vector<std::thread> workers;
      workers.reserve(threads);
      for (unsigned ty = 0; ty < block.y; ++ty) {
        for (unsigned tx = 0; tx < block.x; ++tx) {
          workers.emplace_back([=] {
            threadIdx = uint3{tx, ty, 0};
            blockIdx = uint3{bx, by, 0};
            kernel(arguments...);
          });
        }
      }
      for (std::thread& worker : workers) worker.join();
      current_block = nullptr;
      pthread_barrier_destroy(&state.barrier);
    }
  }
}

}  // namespace posekit::cuda::emulation
