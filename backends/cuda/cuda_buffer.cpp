#include "cuda_buffer.hpp"

#include "cuda_check.hpp"

#include <string>
#include <utility>

namespace posekit::cuda {

DeviceBuffer::DeviceBuffer(std::size_t bytes, const char* what) { reserve(bytes, what); }

DeviceBuffer::~DeviceBuffer() { release(); }

DeviceBuffer::DeviceBuffer(DeviceBuffer&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      bytes_(std::exchange(other.bytes_, 0)),
      ordinal_(other.ordinal_) {}

DeviceBuffer& DeviceBuffer::operator=(DeviceBuffer&& other) noexcept {
  if (this != &other) {
    release();
    data_ = std::exchange(other.data_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
    ordinal_ = other.ordinal_;
  }
  return *this;
}

void DeviceBuffer::reserve(std::size_t bytes, const char* what) {
  if (bytes <= bytes_) return;
  release();
  POSEKIT_CUDA_CHECK(cudaGetDevice(&ordinal_));
  void* data = nullptr;
  const cudaError_t allocated = cudaMalloc(&data, bytes);
  if (allocated != cudaSuccess) {
    const std::string call =
        "cudaMalloc(" + std::to_string(bytes) + " bytes for the " + what + ")";
    check(allocated, call.c_str(), __FILE__, __LINE__);
  }
  data_ = data;
  bytes_ = bytes;
}

void DeviceBuffer::release() noexcept {
  if (data_ == nullptr) return;
  // The memory belongs to the device it was allocated on, which need not be current here. Errors
  // are ignored: at process exit the runtime may already be gone, and a destructor cannot throw.
  int current = 0;
  const bool switched = cudaGetDevice(&current) == cudaSuccess && current != ordinal_ &&
                        cudaSetDevice(ordinal_) == cudaSuccess;
  cudaFree(data_);
  if (switched) cudaSetDevice(current);
  cudaGetLastError();
  data_ = nullptr;
  bytes_ = 0;
}

}  // namespace posekit::cuda
