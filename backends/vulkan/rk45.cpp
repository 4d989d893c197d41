// RK45 batch integration on Vulkan: the particles in batches that fit one storage buffer; for each
// batch, rounds of shaders/rk45_integrate.comp, in which every running particle attempts up to
// steps_per_round adaptive steps on its own and keeps its state on the device. Rounds go out in
// submissions of 1, 2, 4, ... 16 dispatches until no particle runs; steps_per_round keeps one
// round within the driver's loop budget (loop_budget.hpp), so that on GPUs a single round
// usually finishes everything.
#include "loop_budget.hpp"
#include "shader_interface.hpp"
#include "vulkan_device.hpp"

#include "common/kernel_math.h"
#include "common/rk45_counters.hpp"
#include <posekit/error.hpp>

#include <string>

namespace posekit::vulkan {
namespace {

constexpr std::uint32_t kMostRoundsPerSubmission = 16;

// A particle at `x` as pk_rk45_begin starts it.
Rk45State initial_state(const Rk45Options& options, double x, double y, double z) {
  pk_rk45_controller controller;
  pk_rk45_begin(&controller, options.t_begin, options.t_end, options.relative_tolerance,
                options.absolute_tolerance, options.initial_step, options.min_step,
                options.max_steps);
  return Rk45State{{x, y, z, controller.t},
                   {0.0, 0.0, 0.0, controller.h},
                   {controller.accepted_steps, controller.rejected_steps,
                    controller.rhs_evaluations, controller.status},
                   {controller.previous_rejected, 0, 0, 0}};
}

}  // namespace

std::vector<Rk45ParticleStats> VulkanDevice::do_integrate_rk45(
    const DeviceField& field, Eigen::Ref<Eigen::MatrixX3d> positions, const Rk45Options& options) {
  const VulkanField& vulkan_field = uploaded<VulkanField>(field);
  const Eigen::Index count = positions.rows();
  std::vector<Rk45ParticleStats> stats(static_cast<std::size_t>(count));
  const auto centers = static_cast<std::uint64_t>(vulkan_field.center_count());
  const std::uint64_t steps_per_round = rk45_steps_per_round(
      centers, loop_iterations_, static_cast<std::uint64_t>(options.max_steps));
  if (steps_per_round == 0) {
    throw DeviceError("integrate_rk45: one RK45 step through a field of " +
                      std::to_string(centers) + " centers takes more loop iterations than " +
                      context_->description().driver + " allows one shader invocation (" +
                      std::to_string(loop_iterations_) + ")");
  }
  // Each round moves every running particle by at least one attempt; twice the rounds that
  // max_steps allows means the device is not making progress.
  const std::uint64_t round_limit =
      2 * ((static_cast<std::uint64_t>(options.max_steps) + steps_per_round - 1) /
           steps_per_round) +
      2;

  run("integrate_rk45", [&] {
    const Eigen::Index batch = batch_size(sizeof(Rk45State));
    for (Eigen::Index first = 0; first < count; first += batch) {
      const Eigen::Index n = std::min(batch, count - first);
      const VkDeviceSize state_bytes = static_cast<VkDeviceSize>(n) * sizeof(Rk45State);
      Buffer& buffer = rk45_states_.at_least(state_bytes);
      auto* states = buffer.as<Rk45State>();
      bool running = false;
      for (Eigen::Index i = 0; i < n; ++i) {
        states[i] = initial_state(options, positions(first + i, 0), positions(first + i, 1),
                                  positions(first + i, 2));
        running |= states[i].counters[3] == PK_RK45_RUNNING;
      }
      rk45_->write(0, kInputBinding, {{buffer.handle(), 0, state_bytes}});
      vulkan_field.bind_to(*rk45_, 0);
      Rk45Push push{};
      push.t_end = options.t_end;
      push.direction = options.t_end >= options.t_begin ? 1.0 : -1.0;
      push.relative_tolerance = options.relative_tolerance;
      push.absolute_tolerance = options.absolute_tolerance;
      push.min_step = options.min_step;
      push.max_steps = options.max_steps;
      push.particle_count = static_cast<std::uint32_t>(n);
      push.center_count = static_cast<std::uint32_t>(centers);
      push.steps_per_round =
          static_cast<std::uint32_t>(std::min<std::uint64_t>(steps_per_round, UINT32_MAX));
      const auto groups = static_cast<std::uint32_t>((n + kWorkGroupSize - 1) / kWorkGroupSize);

      std::uint64_t rounds = 0;
      std::uint32_t rounds_per_submission = 1;
      while (running) {
        CommandSlot& slot = *slots_[0];
        const VkCommandBuffer commands = slot.begin();
        rk45_->bind(commands, 0, &push);
        for (std::uint32_t r = 0; r < rounds_per_submission; ++r) {
          if (r > 0) record_shader_to_shader_barrier(commands);
          vkCmdDispatch(commands, groups, 1, 1);
        }
        record_shader_to_host_barrier(commands);
        slot.submit();
        slot.wait();
        rounds += rounds_per_submission;
        running = false;
        for (Eigen::Index i = 0; i < n; ++i) {
          if (states[i].flags[1] != 0) {
            throw DeviceError(
                "integrate_rk45: a sum over " + std::to_string(centers) +
                " centers was cut short by the driver's limit on loop iterations of " +
                context_->description().driver);
          }
          running |= states[i].counters[3] == PK_RK45_RUNNING;
        }
        if (running && rounds >= round_limit) {
          throw DeviceError("integrate_rk45: particles still running after " +
                            std::to_string(rounds) + " rounds of at most " +
                            std::to_string(steps_per_round) + " steps with max_steps " +
                            std::to_string(options.max_steps));
        }
        rounds_per_submission = std::min(2 * rounds_per_submission, kMostRoundsPerSubmission);
      }
      for (Eigen::Index i = 0; i < n; ++i) {
        const Rk45State& state = states[i];
        for (int k = 0; k < 3; ++k) positions(first + i, k) = state.position_time[k];
        stats[static_cast<std::size_t>(first + i)] = backends::particle_stats(state.counters);
      }
    }
  });
  return stats;
}

}  // namespace posekit::vulkan
