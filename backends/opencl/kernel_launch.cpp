#include "kernel_launch.hpp"

#include "chunking.hpp"

#include <posekit/error.hpp>

namespace posekit::opencl {

cl::Buffer make_buffer(const OpenClRuntime& runtime, cl_mem_flags flags, std::size_t bytes,
                       const void* host, const char* what) {
  cl_int status = CL_SUCCESS;
  cl::Buffer buffer(runtime.context, flags, bytes, const_cast<void*>(host), &status);
  if (status != CL_SUCCESS) {
    check(status, ("clCreateBuffer(" + std::string(what) + ", " + std::to_string(bytes) +
                   " bytes)").c_str(),
          __FILE__, __LINE__);
  }
  return buffer;
}

const cl::Buffer& scratch_buffer(OpenClRuntime& runtime, Scratch kind, std::size_t bytes) {
  static constexpr const char* kNames[kScratchKinds] = {
      "points", "centers", "block tile", "values", "particle positions", "particle statistics"};
  const auto index = static_cast<std::size_t>(kind);
  OpenClRuntime::ScratchBuffer& slot = runtime.scratch[index];
  if (slot.bytes < bytes) {
    slot.buffer = cl::Buffer();  // release the old one before asking for a larger one
    slot.bytes = 0;
    slot.buffer = make_buffer(runtime, CL_MEM_READ_WRITE, bytes, nullptr, kNames[index]);
    slot.bytes = bytes;
  }
  return slot.buffer;
}

void write_buffer(const OpenClRuntime& runtime, const cl::Buffer& buffer,
                  const std::vector<double>& values) {
  POSEKIT_CL_CHECK(runtime.queue.enqueueWriteBuffer(buffer, CL_TRUE, 0,
                                                    values.size() * sizeof(double), values.data()),
                   "clEnqueueWriteBuffer");
}

void read_columns(const OpenClRuntime& runtime, const cl::Buffer& buffer,
                  Eigen::Index buffer_stride, Eigen::Index rows, Eigen::Index columns, double* host,
                  Eigen::Index host_stride, Eigen::Index first_row, Eigen::Index first_column) {
  if (rows == 0 || columns == 0) return;
  constexpr std::size_t kDouble = sizeof(double);
  const cl::array<cl::size_type, 3> buffer_origin{0, 0, 0};
  const cl::array<cl::size_type, 3> host_origin{static_cast<std::size_t>(first_row) * kDouble,
                                                static_cast<std::size_t>(first_column), 0};
  const cl::array<cl::size_type, 3> region{static_cast<std::size_t>(rows) * kDouble,
                                           static_cast<std::size_t>(columns), 1};
  POSEKIT_CL_CHECK(
      runtime.queue.enqueueReadBufferRect(
          buffer, CL_TRUE, buffer_origin, host_origin, region,
          static_cast<std::size_t>(buffer_stride) * kDouble, 0,
          static_cast<std::size_t>(host_stride) * kDouble, 0, host),
      "clEnqueueReadBufferRect");
}

void launch(const OpenClRuntime& runtime, const cl::Kernel& kernel, std::size_t items,
            std::size_t group, const char* name) {
  const std::size_t global = (items + group - 1) / group * group;
  const cl_int status = runtime.queue.enqueueNDRangeKernel(kernel, cl::NullRange,
                                                           cl::NDRange(global), cl::NDRange(group));
  if (status != CL_SUCCESS) {
    check(status, ("clEnqueueNDRangeKernel(" + std::string(name) + ")").c_str(), __FILE__,
          __LINE__);
  }
}

}  // namespace posekit::opencl
