// Batched RK45: every invocation integrates one particle through dx/dt = f(x, t), f the uploaded
// RBF field, with its own adaptive Dormand-Prince 5(4) steps (Device::integrate_rk45;
// backends/vulkan/rk45.cpp). Mirrors the macro PK_RK45_INTEGRATE_PARTICLE of kernel_math.h, with
// the seven stage derivatives in named variables k1..k7 instead of the array k[21].
//
// A dispatch is one round: each particle still running attempts up to steps_per_round steps, then
// leaves its whole state (position, time, k1, step, counters) in `states` for the next round. The
// host sizes rounds to the device's loop budget (see rbf_field.glsl) and submits rounds until
// every particle has finished: a bounded number of dispatches, no host work between steps.
//
// Control flow stays uniform within a subgroup: while any particle of the subgroup runs, every
// invocation evaluates the field (those whose particle has stopped on their last position, without
// using the result). The uniform buffers of the field are indexed by the chunk number, which the
// specification requires to be uniform across the active invocations and which lavapipe reads
// from the subgroup's first lane, active or not.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require

#include "rbf_field.glsl"

layout(local_size_x = 64) in;

// Keep in step with Rk45State in backends/vulkan/shader_interface.hpp.
struct Rk45State {
  dvec4 position_time;  // x, y, z, t
  dvec4 k1_step;        // k1 (the derivative at x, t), h (the controller's next trial step)
  ivec4 counters;       // accepted steps, rejected steps, field evaluations, status
  ivec4 flags;          // previous attempt rejected, a field sum was cut short, unused, unused
};

layout(std430, set = 0, binding = 0) buffer States {
  Rk45State states[];
};

// Keep in step with Rk45Push in backends/vulkan/shader_interface.hpp.
layout(push_constant) uniform Push {
  double t_end;
  double direction;
  double relative_tolerance;
  double absolute_tolerance;
  double min_step;
  int max_steps;
  uint particle_count;
  uint center_count;
  uint steps_per_round;
} push;

bool complete = true;

dvec3 f(dvec3 x, double t) { return rbf_field_value(dvec4(x, t), push.center_count, complete); }

void main() {
  const uint i = gl_GlobalInvocationID.x;
  // Invocations past the batch take part in the subgroup's loops with particle 0's state and
  // never write.
  const bool in_batch = i < push.particle_count;
  const Rk45State state = states[in_batch ? i : 0u];
  // The controller pk_rk45_begin set up on the host, as the previous round left it.
  pk_rk45_controller c;
  c.t = state.position_time.w;
  c.t_end = push.t_end;
  c.direction = push.direction;
  c.h = state.k1_step.w;
  c.relative_tolerance = push.relative_tolerance;
  c.absolute_tolerance = push.absolute_tolerance;
  c.min_step = push.min_step;
  c.max_steps = push.max_steps;
  c.accepted_steps = state.counters.x;
  c.rejected_steps = state.counters.y;
  c.rhs_evaluations = state.counters.z;
  c.status = in_batch ? state.counters.w : PK_RK45_OK;
  c.previous_rejected = state.flags.x != 0;
  c.reaches_end = false;
  dvec3 x = state.position_time.xyz;
  dvec3 k1 = state.k1_step.xyz;

  // One field evaluation per pass, at a single call site (the shader stays small): stage 1 is
  // the first evaluation of a particle that starts, stages 2..7 those of a step. The stage is the
  // same in every invocation of the subgroup.
  bool starts = c.status == PK_RK45_RUNNING && c.rhs_evaluations == 0;
  uint attempts = 0u;
  bool steps = c.status == PK_RK45_RUNNING && attempts < push.steps_per_round;
  uint stage = subgroupAny(starts) ? 1u : 2u;
  pk_rk45_controller trial = c;
  double step = 0.0LF;
  dvec3 k2 = dvec3(0.0LF), k3 = dvec3(0.0LF), k4 = dvec3(0.0LF), k5 = dvec3(0.0LF);
  dvec3 k6 = dvec3(0.0LF), x_new = dvec3(0.0LF);
  while (stage != 2u || subgroupAny(steps)) {
    dvec3 y;
    double fraction;
    switch (stage) {
      case 1u:
        y = x;
        fraction = 0.0LF;
        break;
      case 2u:
        trial = c;
        step = pk_rk45_trial_step(trial);
        y = pk_rk45_stage2_position(step, x, k1);
        fraction = PK_DP_C2;
        break;
      case 3u:
        y = pk_rk45_stage3_position(step, x, k1, k2);
        fraction = PK_DP_C3;
        break;
      case 4u:
        y = pk_rk45_stage4_position(step, x, k1, k2, k3);
        fraction = PK_DP_C4;
        break;
      case 5u:
        y = pk_rk45_stage5_position(step, x, k1, k2, k3, k4);
        fraction = PK_DP_C5;
        break;
      case 6u:
        y = pk_rk45_stage6_position(step, x, k1, k2, k3, k4, k5);
        fraction = PK_DP_C6;
        break;
      default:
        x_new = pk_rk45_stage7_position(step, x, k1, k3, k4, k5, k6);
        y = x_new;
        fraction = PK_DP_C7;
        break;
    }
    // Stage 1 evaluates at c.t itself (pk_rk45_stage_time's fraction 0 would give the same).
    const dvec3 value = f(y, stage == 1u ? c.t : pk_rk45_stage_time(c, fraction, step));
    switch (stage) {
      case 1u:
        if (starts) {
          k1 = value;
          pk_rk45_record_first_evaluation(c, k1);
        }
        steps = c.status == PK_RK45_RUNNING && attempts < push.steps_per_round;
        break;
      case 2u: k2 = value; break;
      case 3u: k3 = value; break;
      case 4u: k4 = value; break;
      case 5u: k5 = value; break;
      case 6u: k6 = value; break;
      default:
        if (steps) {
          c = trial;
          pk_rk45_finish_step(c, step, x, k1, k3, k4, k5, k6, value, x_new);
          ++attempts;
        }
        steps = c.status == PK_RK45_RUNNING && attempts < push.steps_per_round;
        break;
    }
    stage = stage == 7u ? 2u : stage + 1u;
  }
  if (!in_batch) return;
  Rk45State next;
  next.position_time = dvec4(x, c.t);
  next.k1_step = dvec4(k1, c.h);
  next.counters = ivec4(c.accepted_steps, c.rejected_steps, c.rhs_evaluations, c.status);
  next.flags = ivec4(c.previous_rejected ? 1 : 0, complete ? state.flags.y : 1, 0, 0);
  states[i] = next;
}
