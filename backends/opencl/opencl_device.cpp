// The OpenCL device: context, in-order queue and the program, built once when the device is
// created; the operations live in rbf_assembly.cpp, rbf_evaluation.cpp and rk45.cpp.
#include "opencl_device.hpp"

#include "chunking.hpp"
#include "opencl_discovery.hpp"
#include "opencl_error.hpp"
#include "opencl_operations.hpp"
#include "opencl_program.hpp"
#include "opencl_program_source.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <string>

namespace posekit::opencl {
namespace {

// An assembly tile is scratch memory beside the caller's block; 256 MiB tiles keep that overhead
// bounded while each launch still runs long enough (tens of milliseconds) to hide its cost.
constexpr std::uint64_t kMaxTileBytes = std::uint64_t{256} << 20;

int choose_vector_width(const cl::Device& device, int requested) {
  if (requested != 0) return requested;
  cl_uint preferred = 0;
  device.getInfo(CL_DEVICE_PREFERRED_VECTOR_WIDTH_DOUBLE, &preferred);
  // Wide vector units (AVX-512 behind PoCL) ask for 8; everything else gets 4, which a GPU
  // compiler splits into scalar lanes at no loss.
  return preferred >= 8 ? 8 : 4;
}

// The work-group size for `kernel`: `wanted`, within what the device allows for it.
std::size_t group_size(const cl::Kernel& kernel, const cl::Device& device, std::size_t wanted) {
  std::size_t allowed = 0;
  if (kernel.getWorkGroupInfo(device, CL_KERNEL_WORK_GROUP_SIZE, &allowed) != CL_SUCCESS ||
      allowed == 0) {
    return 1;
  }
  return std::min(wanted, allowed);
}

class OpenClDevice final : public Device {
 public:
  OpenClDevice(const DiscoveredDevice& found, const OpenClDeviceOptions& options)
      : Device(Calls::serialized), info_(describe_device(found)) {
    runtime_.device = found.device;
    runtime_.id = id();
    cl_int status = CL_SUCCESS;
    runtime_.context = cl::Context(found.device, nullptr, nullptr, nullptr, &status);
    POSEKIT_CL_CHECK(status, "clCreateContext");
    runtime_.queue = cl::CommandQueue(runtime_.context, found.device, 0, &status);
    POSEKIT_CL_CHECK(status, "clCreateCommandQueue");

    runtime_.vector_width = choose_vector_width(found.device, options.vector_width);
    const cl::Program program =
        build_program(runtime_.context, found.device, program_source(),
                      "-cl-std=CL1.2 -DPK_VECTOR_WIDTH=" + std::to_string(runtime_.vector_width) +
                          " -DPK_ASSEMBLY_COLUMNS=" + std::to_string(kAssemblyColumns));
    runtime_.assemble = create_kernel(program, "pk_rbf_assemble");
    runtime_.evaluate = create_kernel(program, "pk_rbf_evaluate");
    runtime_.integrate = create_kernel(program, "pk_rk45_integrate");

    runtime_.max_buffer_bytes = found.max_allocation_bytes;
    if (options.max_buffer_bytes != 0) {
      runtime_.max_buffer_bytes = std::min(runtime_.max_buffer_bytes, options.max_buffer_bytes);
    }
    runtime_.max_buffer_bytes = std::max(runtime_.max_buffer_bytes, kMinimumBufferBytes);
    runtime_.max_tile_bytes = std::min(runtime_.max_buffer_bytes, kMaxTileBytes);
    info_.max_buffer_bytes = runtime_.max_buffer_bytes;

    // A CPU device runs each work-group on one thread: small groups let the threads share out
    // points and particles (whose step counts differ) evenly. A GPU wants groups of whole warps.
    // Assembly work-items are short, so its groups are larger on every device.
    const bool cpu = found.is_cpu;
    runtime_.assemble_group = group_size(runtime_.assemble, found.device, 64);
    runtime_.evaluate_group = group_size(runtime_.evaluate, found.device, cpu ? 16 : 64);
    runtime_.integrate_group = group_size(runtime_.integrate, found.device, cpu ? 4 : 64);
  }

  DeviceInfo info() const override { return info_; }

  // Serialized: the operations share one in-order queue and scratch buffers.
 protected:
  void do_assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                             const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                             Eigen::Ref<Eigen::MatrixXd> block) override {
    opencl::assemble_rbf_block(runtime_, points, centers, with_polynomial, block);
  }

  std::unique_ptr<DeviceField> do_upload_field(const RbfField& field) override {
    return std::make_unique<OpenClField>(runtime_, field);
  }

  void do_evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                       Eigen::Ref<Eigen::MatrixX3d> values) override {
    opencl::evaluate_rbf(runtime_, uploaded<OpenClField>(field), points, values);
  }

  std::vector<Rk45ParticleStats> do_integrate_rk45(const DeviceField& field,
                                                   Eigen::Ref<Eigen::MatrixX3d> positions,
                                                   const Rk45Options& options) override {
    return opencl::integrate_rk45(runtime_, uploaded<OpenClField>(field), positions, options);
  }

 private:
  DeviceInfo info_;
  OpenClRuntime runtime_;
};

}  // namespace

std::unique_ptr<Device> make_opencl_device(const OpenClDeviceOptions& options) {
  if (options.max_buffer_bytes != 0 && options.max_buffer_bytes < kMinimumBufferBytes) {
    throw ArgumentError("make_opencl_device: max_buffer_bytes must be 0 (the device's limit) or at "
                        "least " + std::to_string(kMinimumBufferBytes) + ", got " +
                        std::to_string(options.max_buffer_bytes));
  }
  if (options.vector_width != 0 && options.vector_width != 2 && options.vector_width != 4 &&
      options.vector_width != 8) {
    throw ArgumentError("make_opencl_device: vector_width must be 0, 2, 4 or 8, got " +
                        std::to_string(options.vector_width));
  }
  const Discovery discovery = discover_device();
  if (!discovery.device) throw DeviceError("no OpenCL device: " + discovery.reason);
  return std::make_unique<OpenClDevice>(*discovery.device, options);
}

}  // namespace posekit::opencl
