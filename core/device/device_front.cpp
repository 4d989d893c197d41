// The public side of every Device: the checks that all backends make alike, the lock of a
// backend that takes one caller at a time, and the forwarding to the backend's operation.
#include <posekit/device.hpp>
#include <posekit/error.hpp>

#include <atomic>
#include <limits>
#include <string>

namespace posekit {
namespace {

// Fields remember their device by this number rather than by its address, which could be reused.
std::uint64_t next_device_id() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

void check_block_shape(Eigen::Index point_count, Eigen::Index columns, bool with_polynomial,
                       const Eigen::Ref<Eigen::MatrixXd>& block) {
  if (block.rows() != point_count || block.cols() != columns) {
    throw ArgumentError("assemble_rbf_block: block is " + std::to_string(block.rows()) + " by " +
                        std::to_string(block.cols()) + " but must be " +
                        std::to_string(point_count) + " by " + std::to_string(columns) +
                        " (#points by #centers" +
                        (with_polynomial ? " + 15 polynomial columns)" : ")"));
  }
}

// Every backend indexes centers with int.
void check_center_count(const char* operation, Eigen::Index count) {
  if (count > std::numeric_limits<int>::max() - kRbfPolynomialTerms) {
    throw ArgumentError(std::string(operation) + ": " + std::to_string(count) +
                        " centers, more than a device indexes");
  }
}

void check_field(const RbfField& field) {
  check_center_count("upload_field", field.centers.rows());
  if (field.weights.rows() != field.centers.rows()) {
    throw ArgumentError("upload_field: field.weights has " + std::to_string(field.weights.rows()) +
                        " rows but field.centers has " + std::to_string(field.centers.rows()) +
                        " (one weight row per center)");
  }
}

void check_values_shape(Eigen::Index point_count, const Eigen::Ref<Eigen::MatrixX3d>& values) {
  if (values.rows() != point_count) {
    throw ArgumentError("evaluate_rbf: values has " + std::to_string(values.rows()) +
                        " rows but points has " + std::to_string(point_count) +
                        " (values must be #points by 3)");
  }
}

void check_owner(const Device& device, const DeviceField& field, const char* operation) {
  if (field.device_id() != device.id()) {
    throw ArgumentError(std::string(operation) +
                        ": field was uploaded to another device (upload it to this one)");
  }
}

}  // namespace

Device::Device(Calls calls) : id_(next_device_id()), calls_(calls) {}

std::unique_lock<std::mutex> Device::enter() {
  if (calls_ == Calls::serialized) return std::unique_lock<std::mutex>(mutex_);
  return {};
}

void Device::assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                                const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                                Eigen::Ref<Eigen::MatrixXd> block) {
  check_center_count("assemble_rbf_block", centers.rows());
  const Eigen::Index columns = centers.rows() + (with_polynomial ? kRbfPolynomialTerms : 0);
  check_block_shape(points.rows(), columns, with_polynomial, block);
  if (points.rows() == 0 || columns == 0) return;
  const auto lock = enter();
  do_assemble_rbf_block(points, centers, with_polynomial, block);
}

std::unique_ptr<DeviceField> Device::upload_field(const RbfField& field) {
  check_field(field);
  const auto lock = enter();
  return do_upload_field(field);
}

void Device::evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                          Eigen::Ref<Eigen::MatrixX3d> values) {
  check_owner(*this, field, "evaluate_rbf");
  check_values_shape(points.rows(), values);
  if (points.rows() == 0) return;
  const auto lock = enter();
  do_evaluate_rbf(field, points, values);
}

std::vector<Rk45ParticleStats> Device::integrate_rk45(const DeviceField& field,
                                                      Eigen::Ref<Eigen::MatrixX3d> positions,
                                                      const Rk45Options& options) {
  check_owner(*this, field, "integrate_rk45");
  validate_rk45_options(options);
  if (positions.rows() == 0) return {};
  const auto lock = enter();
  return do_integrate_rk45(field, positions, options);
}

}  // namespace posekit
