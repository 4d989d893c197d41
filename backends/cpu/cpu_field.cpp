#include "cpu_field.hpp"

#include "common/kernel_math.h"

namespace posekit::cpu {

CpuField::CpuField(const RbfField& field, std::uint64_t device_id)
    : DeviceField(device_id, static_cast<int>(field.centers.rows())),
      polynomial_(field.polynomial) {
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
