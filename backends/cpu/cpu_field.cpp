#include "cpu_field.hpp"

#include <posekit/kernel_math.h>
#include <posekit/error.hpp>

#include <string>

namespace posekit::cpu {

CpuField::CpuField(const RbfField& field, std::uint64_t device_id)
    : polynomial_(field.polynomial), device_id_(device_id) {
  if (field.weights.rows() != field.centers.rows()) {
    throw ArgumentError("upload_field: field.weights has " + std::to_string(field.weights.rows()) +
                        " rows but field.centers has " + std::to_string(field.centers.rows()) +
                        " (one weight row per center)");
  }
  columns_.resize(field.centers.rows(), 7);
  columns_.leftCols<4>() = field.centers;
  columns_.rightCols<3>() = field.weights;
}

void CpuField::value_at(RbfSumKernel kernel, const double* point, double* value) const {
  kernel(centers(), weights(), columns_.rows(), point, value);
  for (int component = 0; component < 3; ++component) {
    value[component] += pk_polynomial_value(polynomial_.col(component).data(), point[0], point[1],
                                            point[2], point[3]);
  }
}

}  // namespace posekit::cpu
