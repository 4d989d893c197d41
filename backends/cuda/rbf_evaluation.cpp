// RBF evaluation on a CUDA device: points go over in chunks that fit the scratch budget, one launch
// per chunk (kernels/cuda/rbf_evaluate.cu), one thread per point.
#include "chunking.hpp"
#include "cuda_check.hpp"
#include "cuda_kernels.hpp"
#include "cuda_operations.hpp"

#include <algorithm>

namespace posekit::cuda {

void evaluate_rbf(CudaContext& context, const CudaField& field,
                  const Eigen::Ref<const Points4>& points, Eigen::Ref<Eigen::MatrixX3d> values) {
  const Eigen::Index count = points.rows();
  // The points' four columns are the larger of the two buffers.
  const Eigen::Index capacity =
      std::min(count, items_per_chunk(chunk_limits(context.max_chunk_bytes), 4 * sizeof(double)));
  double* const point_buffer =
      context.scratch_buffer(Scratch::points, 4 * sizeof(double) * capacity).as<double>();
  double* const value_buffer =
      context.scratch_buffer(Scratch::values, 3 * sizeof(double) * capacity).as<double>();
  const FieldView view = field.view();
  for (Eigen::Index first = 0; first < count; first += capacity) {
    const Eigen::Index rows = std::min(capacity, count - first);
    copy_columns(context, point_buffer, capacity, points.data() + first, points.outerStride(), rows,
                 4, cudaMemcpyHostToDevice);
    const PointsView chunk{point_buffer, static_cast<int>(rows), static_cast<int>(capacity)};
    POSEKIT_CUDA_CHECK(launch_rbf_evaluate(view, chunk, value_buffer, context.stream));
    copy_columns(context, values.data() + first, values.outerStride(), value_buffer, capacity,
                 rows, 3, cudaMemcpyDeviceToHost);
  }
  context.synchronize();
}

}  // namespace posekit::cuda
