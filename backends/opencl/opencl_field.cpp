#include "opencl_field.hpp"

#include "chunking.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <limits>
#include <string>

namespace posekit::opencl {

OpenClField::OpenClField(const OpenClRuntime& runtime, const RbfField& field)
    : device_id_(runtime.id) {
  const Eigen::Index count = field.centers.rows();
  if (field.weights.rows() != count) {
    throw ArgumentError("upload_field: field.weights has " + std::to_string(field.weights.rows()) +
                        " rows but field.centers has " + std::to_string(count) +
                        " (one weight row per center)");
  }
  if (count > std::numeric_limits<int>::max()) {
    throw ArgumentError("upload_field: field.centers has " + std::to_string(count) +
                        " rows, more than an OpenCL kernel can index");
  }
  center_count_ = static_cast<int>(count);
  const Eigen::Index width = runtime.vector_width;
  const Eigen::Index per_part = items_per_buffer(runtime.max_buffer_bytes, 7 * sizeof(double), width);
  Eigen::Index first = 0;
  do {
    const Eigen::Index part_count = std::min(per_part, count - first);
    const Eigen::Index stride = round_up(std::max<Eigen::Index>(part_count, 1), width);
    Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(stride, 7);
    columns.topLeftCorner(part_count, 4) = field.centers.middleRows(first, part_count);
    columns.block(0, 4, part_count, 3) = field.weights.middleRows(first, part_count);
    Part part;
    part.buffer = make_buffer(runtime, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                              static_cast<std::size_t>(columns.size()) * sizeof(double),
                              columns.data(), "field centers");
    part.count = static_cast<int>(part_count);
    part.stride = static_cast<int>(stride);
    parts_.push_back(std::move(part));
    first += part_count;
  } while (first < count);
  const RbfPolynomial polynomial = field.polynomial;
  polynomial_ = make_buffer(runtime, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                            sizeof(double) * kRbfPolynomialTerms * 3, polynomial.data(),
                            "field polynomial");
}

}  // namespace posekit::opencl
