#include "cuda_field.hpp"

#include "chunking.hpp"
#include "cuda_check.hpp"

#include <posekit/error.hpp>

#include <string>

namespace posekit::cuda {

CudaField::CudaField(const CudaContext& context, const RbfField& field)
    : DeviceField(context.id, static_cast<int>(field.centers.rows())) {
  const Eigen::Index count = field.centers.rows();
  if (count > kMaxChunkItems) {
    throw ArgumentError("upload_field: field.centers has " + std::to_string(count) +
                        " rows, more than the CUDA kernels index (" +
                        std::to_string(kMaxChunkItems) + ")");
  }
  const std::size_t doubles = static_cast<std::size_t>(7 * count + 3 * kRbfPolynomialTerms);
  memory_.reserve(doubles * sizeof(double), "field");
  double* columns = memory_.as<double>();
  // RbfField's matrices are column-major without padding: each is one contiguous copy.
  const std::size_t center_bytes = static_cast<std::size_t>(4 * count) * sizeof(double);
  const std::size_t weight_bytes = static_cast<std::size_t>(3 * count) * sizeof(double);
  if (count > 0) {
    POSEKIT_CUDA_CHECK(cudaMemcpyAsync(columns, field.centers.data(), center_bytes,
                                       cudaMemcpyHostToDevice, context.stream));
    POSEKIT_CUDA_CHECK(cudaMemcpyAsync(columns + 4 * count, field.weights.data(), weight_bytes,
                                       cudaMemcpyHostToDevice, context.stream));
  }
  POSEKIT_CUDA_CHECK(cudaMemcpyAsync(columns + 7 * count, field.polynomial.data(),
                                     sizeof(double) * 3 * kRbfPolynomialTerms,
                                     cudaMemcpyHostToDevice, context.stream));
  context.synchronize();
}

FieldView CudaField::view() const {
  FieldView view;
  view.columns = memory_.as<const double>();
  view.polynomial = view.columns + 7 * static_cast<std::size_t>(center_count());
  view.count = center_count();
  return view;
}

}  // namespace posekit::cuda
