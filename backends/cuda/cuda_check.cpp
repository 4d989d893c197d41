#include "cuda_check.hpp"

#include <posekit/error.hpp>

#include <cstring>

namespace posekit::cuda {
namespace {

// The path from "backends/" on: enough to find the file, without the build machine's folders.
const char* project_path(const char* file) {
  const char* inside = std::strstr(file, "backends/");
  return inside != nullptr ? inside : file;
}

}  // namespace

std::string describe(cudaError_t error) {
  return std::string(cudaGetErrorName(error)) + ": " + cudaGetErrorString(error);
}

void check(cudaError_t error, const char* call, const char* file, int line) {
  if (error == cudaSuccess) return;
  // A launch or argument error stays pending until read; clear it so that the next call does not
  // report it again (an error of the context itself remains and is reported by every call).
  cudaGetLastError();
  throw DeviceError(std::string(call) + " failed with " + describe(error) + " at " +
                    project_path(file) + ":" + std::to_string(line));
}

}  // namespace posekit::cuda
