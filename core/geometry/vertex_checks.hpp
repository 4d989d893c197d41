// Argument checks shared by the geometry functions.
#pragma once

#include <Eigen/Core>

#include <string>

namespace posekit::detail {

/// Throws ArgumentError naming `function` and the first vertex with a NaN or infinite coordinate.
void check_finite_vertices(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const std::string& function);

}  // namespace posekit::detail
