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
  /// Copies `field`; device_id names the device that owns it. Throws ArgumentError when the
  /// weights do not have one row per center.
  CpuField(const RbfField& field, std::uint64_t device_id);

  int center_count() const override { return static_cast<int>(columns_.rows()); }
  std::uint64_t device_id() const { return device_id_; }

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
  std::uint64_t device_id_;
};

}  // namespace posekit::cpu
