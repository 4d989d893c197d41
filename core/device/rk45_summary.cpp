#include <posekit/device.hpp>

namespace posekit {

Rk45Summary summarize(const std::vector<Rk45ParticleStats>& stats) {
  Rk45Summary summary;
  for (const Rk45ParticleStats& particle : stats) {
    summary.accepted_steps += particle.accepted_steps;
    summary.rejected_steps += particle.rejected_steps;
    summary.rhs_evaluations += particle.rhs_evaluations;
    if (particle.status != Rk45Status::ok) ++summary.failures;
  }
  return summary;
}

}  // namespace posekit
