// RK45 batch integration on the CPU: one particle per task, each with its own adaptive
// Dormand-Prince loop (kernel_math.h), every stage one field evaluation at a single point (x, t)
// whose sum over centers is the same vectorized loop as the batch evaluation's.
#include "cpu_operations.hpp"
#include "rbf_kernels.hpp"

#include "common/kernel_math.h"
#include "common/rk45_counters.hpp"
#include <posekit/error.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

namespace posekit::cpu {
namespace {

Rk45ParticleStats integrate_particle(const CpuField& field, RbfSumKernel kernel,
                                     const Rk45Options& options, double* x) {
  pk_rk45_controller controller;
  pk_rk45_begin(&controller, options.t_begin, options.t_end, options.relative_tolerance,
                options.absolute_tolerance, options.initial_step, options.min_step,
                options.max_steps);
  const auto evaluate = [&field, kernel](const double* point, double* derivative) {
    field.value_at(kernel, point, derivative);
  };
  PK_RK45_INTEGRATE_PARTICLE(controller, x, evaluate);
  return backends::particle_stats(controller.accepted_steps, controller.rejected_steps, controller.rhs_evaluations,
                                  controller.status);
}

}  // namespace

std::vector<Rk45ParticleStats> integrate_rk45(const CpuExecution& execution, const CpuField& field,
                                              Eigen::Ref<Eigen::MatrixX3d> positions,
                                              const Rk45Options& options) {
  const Eigen::Index count = positions.rows();
  std::vector<Rk45ParticleStats> stats(static_cast<std::size_t>(count));
  const RbfSumKernel kernel = rbf_sum_kernel(execution.isa);
  // Grain 1: particles need very different numbers of steps, so let idle threads take single ones.
  execution.arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, count, 1),
                      [&](const tbb::blocked_range<Eigen::Index>& range) {
                        for (Eigen::Index i = range.begin(); i < range.end(); ++i) {
                          double x[3] = {positions(i, 0), positions(i, 1), positions(i, 2)};
                          stats[static_cast<std::size_t>(i)] =
                              integrate_particle(field, kernel, options, x);
                          positions(i, 0) = x[0];
                          positions(i, 1) = x[1];
                          positions(i, 2) = x[2];
                        }
                      });
  });
  return stats;
}

}  // namespace posekit::cpu
