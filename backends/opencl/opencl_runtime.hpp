// What the three operations of an OpenCL device share: context, queue, the kernels built once at
// device creation, launch shapes and buffer limits.
#pragma once

#include <CL/opencl.hpp>

#include <array>
#include <cstddef>
#include <cstdint>

namespace posekit::opencl {

/// Columns of the block that one work-item of pk_rbf_assemble computes (PK_ASSEMBLY_COLUMNS).
constexpr int kAssemblyColumns = 8;

/// Buffers an operation needs only while it runs. The device keeps them between calls and grows
/// them on demand: a fresh buffer per call would cost its allocation and, on a CPU device, the page
/// faults of touching new memory, as much as the work itself for a small block.
enum class Scratch { points, centers, tile, values, positions, statistics };
constexpr std::size_t kScratchKinds = 6;

/// The device's objects; the device's mutex guards every use (kernel arguments are shared state).
struct OpenClRuntime {
  cl::Device device;
  cl::Context context;
  cl::CommandQueue queue;
  cl::Kernel assemble;   ///< pk_rbf_assemble (kernels/opencl/rbf_assembly.cl)
  cl::Kernel evaluate;   ///< pk_rbf_evaluate (kernels/opencl/rbf_evaluate.cl)
  cl::Kernel integrate;  ///< pk_rk45_integrate (kernels/opencl/rk45.cl)
  int vector_width = 8;  ///< PK_VECTOR_WIDTH of the program: doubles per vector
  std::uint64_t max_buffer_bytes = 0;  ///< no buffer is larger
  std::uint64_t max_tile_bytes = 0;    ///< no assembly tile (scratch) is larger
  std::size_t assemble_group = 1;      ///< work-group sizes of the three kernels
  std::size_t evaluate_group = 1;
  std::size_t integrate_group = 1;
  std::uint64_t id = 0;  ///< tells fields of this device from those of others

  struct ScratchBuffer {
    cl::Buffer buffer;
    std::size_t bytes = 0;
  };
  std::array<ScratchBuffer, kScratchKinds> scratch;
};

/// The device's scratch buffer `kind`, at least `bytes` (> 0) long (read and write).
const cl::Buffer& scratch_buffer(OpenClRuntime& runtime, Scratch kind, std::size_t bytes);

/// A buffer of `bytes` bytes (> 0) with `flags`, filled from `host` when not null; throws
/// DeviceError naming `what` when the allocation fails.
cl::Buffer make_buffer(const OpenClRuntime& runtime, cl_mem_flags flags, std::size_t bytes,
                       const void* host, const char* what);

}  // namespace posekit::opencl
