// The CUDA backend's three operations, one file each; CudaDevice forwards to them with its mutex
// held and the device current.
#pragma once

#include "cuda_context.hpp"
#include "cuda_field.hpp"

#include <posekit/device.hpp>

#include <vector>

namespace posekit::cuda {

/// Device::assemble_rbf_block (rbf_assembly.cpp).
void assemble_rbf_block(CudaContext& context, const Eigen::Ref<const Points4>& points,
                        const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                        Eigen::Ref<Eigen::MatrixXd> block);

/// Device::evaluate_rbf (rbf_evaluation.cpp).
void evaluate_rbf(CudaContext& context, const CudaField& field,
                  const Eigen::Ref<const Points4>& points, Eigen::Ref<Eigen::MatrixX3d> values);

/// Device::integrate_rk45 (rk45.cpp); options already validated.
std::vector<Rk45ParticleStats> integrate_rk45(CudaContext& context, const CudaField& field,
                                              Eigen::Ref<Eigen::MatrixX3d> positions,
                                              const Rk45Options& options);

}  // namespace posekit::cuda
