// The moves every operation makes: pack host rows for a buffer, set kernel arguments, launch, read
// results back into strided Eigen storage.
#pragma once

#include "opencl_error.hpp"
#include "opencl_runtime.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace posekit::opencl {

/// `rows` rows of `source` (any number of columns, any outer stride) from row `first`, as
/// contiguous columns of `stride` doubles each, zero below the copied rows.
template <typename Source>
std::vector<double> pack_columns(const Source& source, Eigen::Index first, Eigen::Index rows,
                                 Eigen::Index stride) {
  const Eigen::Index columns = source.cols();
  std::vector<double> packed(static_cast<std::size_t>(stride * columns), 0.0);
  Eigen::Map<Eigen::MatrixXd> target(packed.data(), stride, columns);
  target.topRows(rows) = source.middleRows(first, rows);
  return packed;
}

/// Writes `values` to the start of `buffer` (blocking: `values` may be reused right after).
void write_buffer(const OpenClRuntime& runtime, const cl::Buffer& buffer,
                  const std::vector<double>& values);

/// Copies a device buffer of `columns` columns of `buffer_stride` doubles, rows 0 .. rows - 1, into
/// the column-major host matrix at `host` (columns `host_stride` doubles apart), rows
/// first_row .. first_row + rows - 1 and columns first_column .. first_column + columns - 1. One
/// rectangular copy, blocking.
void read_columns(const OpenClRuntime& runtime, const cl::Buffer& buffer,
                  Eigen::Index buffer_stride, Eigen::Index rows, Eigen::Index columns, double* host,
                  Eigen::Index host_stride, Eigen::Index first_row, Eigen::Index first_column);

/// Launches a one-dimensional `kernel` over `items` work-items, rounded up to whole groups.
void launch(const OpenClRuntime& runtime, const cl::Kernel& kernel, std::size_t items,
            std::size_t group, const char* name);

/// Sets the arguments of `kernel` in order; throws DeviceError naming the kernel and the argument's
/// index when one is refused.
template <typename... Values>
void set_arguments(cl::Kernel& kernel, const char* name, const Values&... values) {
  cl_uint index = 0;
  const auto set = [&](const auto& value) {
    const cl_int status = kernel.setArg(index, value);
    if (status != CL_SUCCESS) {
      check(status,
            ("clSetKernelArg(" + std::string(name) + ", " + std::to_string(index) + ")").c_str(),
            __FILE__, __LINE__);
    }
    ++index;
  };
  (set(values), ...);
}

}  // namespace posekit::opencl
