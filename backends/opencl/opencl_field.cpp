#include "opencl_field.hpp"

#include "chunking.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <limits>
#include <string>

namespace posekit::opencl {

OpenClField::OpenClField(const OpenClRuntime& runtime, const RbfField& field)
    : DeviceField(runtime.id, static_cast<int>(field.centers.rows())) {
  const Eigen::Index count = field.centers.rows();
  const Eigen::Index width = runtime.vector_width;
  const Eigen::Index per_part = items_per_chunk(chunk_limits(runtime.max_buffer_bytes), 7 * sizeof(double), width);
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
