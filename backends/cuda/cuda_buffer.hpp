// Device memory owned by an object: freed when the object goes, grown on demand for scratch use.
#pragma once

#include <cstddef>

namespace posekit::cuda {

class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  /// `bytes` (> 0) of memory on the current device; throws DeviceError naming `what` when the
  /// allocation fails.
  DeviceBuffer(std::size_t bytes, const char* what);
  ~DeviceBuffer();
  DeviceBuffer(DeviceBuffer&& other) noexcept;
  DeviceBuffer& operator=(DeviceBuffer&& other) noexcept;
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;

  /// Makes the buffer at least `bytes` long; its contents are lost when it grows.
  void reserve(std::size_t bytes, const char* what);

  void* data() const { return data_; }
  template <typename T>
  T* as() const {
    return static_cast<T*>(data_);
  }
  std::size_t bytes() const { return bytes_; }

 private:
  void release() noexcept;

  void* data_ = nullptr;
  std::size_t bytes_ = 0;
  int ordinal_ = 0;
};

}  // namespace posekit::cuda
