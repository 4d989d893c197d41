// posekit CUDA: one particle's adaptive Dormand-Prince 5(4) integration as a state machine that
// takes one field evaluation at a time. Used by the RK45 kernel (rk45.cu) and compiled for the
// host by the unit tests (tests/unit/cuda), which hold it against PK_RK45_INTEGRATE_PARTICLE.
//
// The loop of PK_RK45_INTEGRATE_PARTICLE (kernel_math.h) cannot run inside a kernel whose field
// evaluation holds barriers, because its trip count differs from thread to thread. The state
// machine takes the macro's decisions in the macro's order: rk45_evaluation_point says where the
// next evaluation happens (stage 1: the start; stages 2..7: the stages of a step, the trial step
// chosen at stage 2), rk45_consume_evaluation stores the value and, after stage 7, accepts or
// rejects the step. The stage derivatives stay in registers on the GPU: after the switch over
// stages is unrolled, every index into k is a constant.
#pragma once

#include "common/kernel_math.h"

#if defined(__CUDACC__)
#define PK_CUDA_FUNCTION __host__ __device__ inline
#else
#define PK_CUDA_FUNCTION inline
#endif

namespace posekit::cuda {

struct Rk45Particle {
  pk_rk45_controller controller;
  double x[3];      // the position
  double x_new[3];  // the fifth-order solution of the step in progress
  double k[3 * PK_DP_STAGES];
  double step;      // signed length of the step in progress
  int stage;        // 1: the first evaluation, 2..7: the stages of a step
};

/// Starts a particle at `start` (3 doubles) with the controls of Rk45Controls' fields. Returns
/// whether it needs integrating (false when t_end == t_begin: it is done, at its start, with no
/// evaluation).
PK_CUDA_FUNCTION bool rk45_start(Rk45Particle& p, const double* start, double t_begin,
                                 double t_end, double relative_tolerance,
                                 double absolute_tolerance, double initial_step, double min_step,
                                 int max_steps) {
  for (int c = 0; c < 3; ++c) p.x[c] = start[c];
  pk_rk45_begin(&p.controller, t_begin, t_end, relative_tolerance, absolute_tolerance,
                initial_step, min_step, max_steps);
  p.stage = 1;
  p.step = 0.0;
  return p.controller.status == PK_RK45_RUNNING;
}

/// Stage kStage (2..7) of the step in progress: where it evaluates the field.
template <int kStage>
PK_CUDA_FUNCTION void rk45_stage_point(Rk45Particle& p, double* point) {
  double* y = kStage == PK_DP_STAGES ? p.x_new : point;
  pk_rk45_stage_position(kStage, p.step, p.x, p.k, y);
  for (int c = 0; c < 3; ++c) point[c] = y[c];
  point[3] = pk_rk45_stage_time(&p.controller, kStage, p.step);
}

/// Writes to point[0..3] (x, y, z, t) where the running particle's next evaluation takes place.
PK_CUDA_FUNCTION void rk45_evaluation_point(Rk45Particle& p, double* point) {
  switch (p.stage) {
    case 1:
      for (int c = 0; c < 3; ++c) point[c] = p.x[c];
      point[3] = p.controller.t;
      break;
    case 2:
      p.step = pk_rk45_trial_step(&p.controller);
      rk45_stage_point<2>(p, point);
      break;
    case 3: rk45_stage_point<3>(p, point); break;
    case 4: rk45_stage_point<4>(p, point); break;
    case 5: rk45_stage_point<5>(p, point); break;
    case 6: rk45_stage_point<6>(p, point); break;
    default: rk45_stage_point<7>(p, point); break;
  }
}

template <int kStage>
PK_CUDA_FUNCTION void rk45_store_derivative(Rk45Particle& p, const double* value) {
  for (int c = 0; c < 3; ++c) p.k[3 * (kStage - 1) + c] = value[c];
}

/// Takes f at the evaluation point (3 doubles) and moves the particle on; afterwards
/// p.controller.status says whether it still runs.
PK_CUDA_FUNCTION void rk45_consume_evaluation(Rk45Particle& p, const double* value) {
  switch (p.stage) {
    case 1:
      rk45_store_derivative<1>(p, value);
      pk_rk45_record_first_evaluation(&p.controller, p.k);
      p.stage = 2;
      break;
    case 2: rk45_store_derivative<2>(p, value); p.stage = 3; break;
    case 3: rk45_store_derivative<3>(p, value); p.stage = 4; break;
    case 4: rk45_store_derivative<4>(p, value); p.stage = 5; break;
    case 5: rk45_store_derivative<5>(p, value); p.stage = 6; break;
    case 6: rk45_store_derivative<6>(p, value); p.stage = 7; break;
    default:
      rk45_store_derivative<7>(p, value);
      pk_rk45_finish_step(&p.controller, p.step, p.x, p.k, p.x_new);
      p.stage = 2;
      break;
  }
}

}  // namespace posekit::cuda
