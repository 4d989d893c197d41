// A field uploaded to the CPU backend: centers and weights as contiguous columns, so that the
// loop over centers reads each coordinate with unit stride.
#pragma once

#include "rbf_kernels.hpp"

#include <posekit/device.hpp>

#include <Eigen/Core>
#include <cstdint>

namespace posekit::cpu {

class CpuField final : public DeviceField {
 public:
  /// Copies `field` (checked by Device::upload_field) for the device numbered device_id.
  CpuField(const RbfField& field, std::uint64_t device_id);

  Columns4 centers() const {
    return {columns_.col(0).data(), columns_.col(1).data(), columns_.col(2).data(),
            columns_.col(3).data()};
  }
  Columns3 weights() const {
    return {columns_.col(4).data(), columns_.col(5).data(), columns_.col(6).data()};
  }

  /// value[0..2] = f(point) for one point (x, y, z, t), the sum over centers done by `kernel`.
  void value_at(RbfSumKernel kernel, const double* point, double* value) const;

 private:
  // Columns: center x, y, z, t, then weight x, y, z. Column-major, so each is contiguous.
  Eigen::Matrix<double, Eigen::Dynamic, 7> columns_;
  RbfPolynomial polynomial_;
};

}  // namespace posekit::cpu
