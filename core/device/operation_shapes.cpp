// The size checks every backend makes before an operation, so that all report a mismatch alike.
#include <posekit/device.hpp>
#include <posekit/error.hpp>

#include <string>

namespace posekit {

Eigen::Index validate_rbf_block_shape(Eigen::Index point_count, Eigen::Index center_count, bool with_polynomial,
                                      const Eigen::Ref<Eigen::MatrixXd>& block) {
  const Eigen::Index columns = center_count + (with_polynomial ? kRbfPolynomialTerms : 0);
  if (block.rows() != point_count || block.cols() != columns) {
    throw ArgumentError("assemble_rbf_block: block is " + std::to_string(block.rows()) + " by " +
                        std::to_string(block.cols()) + " but must be " + std::to_string(point_count) + " by " +
                        std::to_string(columns) + " (#points by #centers" +
                        (with_polynomial ? " + 15 polynomial columns)" : ")"));
  }
  return columns;
}

void validate_rbf_values_shape(Eigen::Index point_count, const Eigen::Ref<Eigen::MatrixX3d>& values) {
  if (values.rows() != point_count) {
    throw ArgumentError("evaluate_rbf: values has " + std::to_string(values.rows()) + " rows but points has " +
                        std::to_string(point_count) + " (values must be #points by 3)");
  }
}

}  // namespace posekit
