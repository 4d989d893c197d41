// The CPU backend's three operations, one file each; CpuDevice forwards to them the arguments
// that Device's front has checked.
#pragma once

#include "cpu_field.hpp"
#include "kernel_isa.hpp"

#include <posekit/device.hpp>

#include <tbb/task_arena.h>

#include <vector>

namespace posekit::cpu {

/// Where an operation runs: the device's thread arena and the instruction set of its hot loops.
struct CpuExecution {
  tbb::task_arena& arena;
  KernelIsa isa;
};

/// Device::assemble_rbf_block (rbf_assembly.cpp).
void assemble_rbf_block(const CpuExecution& execution, const Eigen::Ref<const Points4>& points,
                        const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                        Eigen::Ref<Eigen::MatrixXd> block);

/// Device::evaluate_rbf (rbf_evaluation.cpp).
void evaluate_rbf(const CpuExecution& execution, const CpuField& field,
                  const Eigen::Ref<const Points4>& points, Eigen::Ref<Eigen::MatrixX3d> values);

/// Device::integrate_rk45 (rk45.cpp).
std::vector<Rk45ParticleStats> integrate_rk45(const CpuExecution& execution, const CpuField& field,
                                              Eigen::Ref<Eigen::MatrixX3d> positions,
                                              const Rk45Options& options);

}  // namespace posekit::cpu
