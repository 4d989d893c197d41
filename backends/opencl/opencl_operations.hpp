// The OpenCL backend's three operations, one file each; OpenClDevice forwards to them with its
// mutex held.
#pragma once

#include "opencl_field.hpp"
#include "opencl_runtime.hpp"

#include <posekit/device.hpp>

#include <vector>

namespace posekit::opencl {

/// Device::assemble_rbf_block (rbf_assembly.cpp).
void assemble_rbf_block(OpenClRuntime& runtime, const Eigen::Ref<const Points4>& points,
                        const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                        Eigen::Ref<Eigen::MatrixXd> block);

/// Device::evaluate_rbf (rbf_evaluation.cpp).
void evaluate_rbf(OpenClRuntime& runtime, const OpenClField& field,
                  const Eigen::Ref<const Points4>& points, Eigen::Ref<Eigen::MatrixX3d> values);

/// Device::integrate_rk45 (rk45.cpp); options already validated.
std::vector<Rk45ParticleStats> integrate_rk45(OpenClRuntime& runtime, const OpenClField& field,
                                              Eigen::Ref<Eigen::MatrixX3d> positions,
                                              const Rk45Options& options);

}  // namespace posekit::opencl
