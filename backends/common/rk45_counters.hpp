// What every backend's RK45 kernels leave per particle: four counters (accepted steps, rejected
// steps, field evaluations, and the status code of kernel_math.h), read back as Rk45ParticleStats.
#pragma once

#include "common/kernel_math.h"
#include <posekit/device.hpp>

#include <cstdint>

namespace posekit::backends {

static_assert(static_cast<int>(Rk45Status::ok) == PK_RK45_OK &&
                  static_cast<int>(Rk45Status::max_steps) == PK_RK45_MAX_STEPS &&
                  static_cast<int>(Rk45Status::step_underflow) == PK_RK45_STEP_UNDERFLOW &&
                  static_cast<int>(Rk45Status::non_finite) == PK_RK45_NON_FINITE,
              "Rk45Status and kernel_math.h disagree");

/// The stats of one particle from its four counters, in that order.
inline Rk45ParticleStats particle_stats(std::int32_t accepted, std::int32_t rejected, std::int32_t evaluations,
                                        std::int32_t status) {
  Rk45ParticleStats stats;
  stats.accepted_steps = accepted;
  stats.rejected_steps = rejected;
  stats.rhs_evaluations = evaluations;
  stats.status = static_cast<Rk45Status>(status);
  return stats;
}

/// The same from a record of four consecutive counters.
inline Rk45ParticleStats particle_stats(const std::int32_t* counters) {
  return particle_stats(counters[0], counters[1], counters[2], counters[3]);
}

}  // namespace posekit::backends
