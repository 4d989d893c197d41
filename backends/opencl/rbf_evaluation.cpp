// RBF evaluation on an OpenCL device: points go over in chunks that fit a buffer; each chunk is one
// launch per field part (kernels/opencl/rbf_evaluate.cl), one work-item per point.
#include "chunking.hpp"
#include "kernel_launch.hpp"
#include "opencl_operations.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <string>

namespace posekit::opencl {

void evaluate_rbf(OpenClRuntime& runtime, const OpenClField& field,
                  const Eigen::Ref<const Points4>& points, Eigen::Ref<Eigen::MatrixX3d> values) {
  const Eigen::Index count = points.rows();
  // The points' four columns are the larger of the two buffers.
  const Eigen::Index capacity =
      std::min(count, items_per_chunk(chunk_limits(runtime.max_buffer_bytes), 4 * sizeof(double)));
  const cl::Buffer point_buffer =
      scratch_buffer(runtime, Scratch::points, 4 * sizeof(double) * capacity);
  const cl::Buffer value_buffer =
      scratch_buffer(runtime, Scratch::values, 3 * sizeof(double) * capacity);
  const int stride = static_cast<int>(capacity);
  for (Eigen::Index first = 0; first < count; first += capacity) {
    const Eigen::Index rows = std::min(capacity, count - first);
    write_buffer(runtime, point_buffer, pack_columns(points, first, rows, capacity));
    const std::vector<OpenClField::Part>& parts = field.parts();
    for (std::size_t p = 0; p < parts.size(); ++p) {
      const int first_part = p == 0 ? 1 : 0;
      set_arguments(runtime.evaluate, "pk_rbf_evaluate", parts[p].buffer, parts[p].count,
                    parts[p].stride, field.polynomial(), first_part, point_buffer,
                    static_cast<int>(rows), stride, 1 - first_part, value_buffer);
      launch(runtime, runtime.evaluate, static_cast<std::size_t>(rows), runtime.evaluate_group,
             "pk_rbf_evaluate");
    }
    read_columns(runtime, value_buffer, capacity, rows, 3, values.data(), values.outerStride(),
                 first, 0);
  }
}

}  // namespace posekit::opencl
