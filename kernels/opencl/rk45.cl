/* posekit OpenCL: batched adaptive RK45, one work-item per particle, each running the whole
 * Dormand-Prince loop of kernel_math.h (PK_RK45_INTEGRATE_PARTICLE) with its own steps in this one
 * launch.
 *
 * Positions: three columns of particle_stride doubles, read as start and overwritten with the end
 * (or failure) positions. Statistics: four ints per particle (accepted steps, rejected steps,
 * field evaluations, status). The field is one part in rbf_field.cl's layout.
 */
__kernel void pk_rk45_integrate(__global const double* field, int center_count, int center_stride,
                                __global const double* polynomial, __global double* positions,
                                int particle_count, int particle_stride, double t_begin,
                                double t_end, double relative_tolerance, double absolute_tolerance,
                                double initial_step, double min_step, int max_steps,
                                __global int* stats) {
  const int i = (int)get_global_id(0);
  if (i >= particle_count) return;
  double coefficients[3 * PK_POLYNOMIAL_TERMS];
  double x[3];
  pk_rk45_controller controller;
  pk_load_polynomial(polynomial, coefficients);
  x[0] = positions[i];
  x[1] = positions[particle_stride + i];
  x[2] = positions[2 * (size_t)particle_stride + i];
  pk_rk45_begin(&controller, t_begin, t_end, relative_tolerance, absolute_tolerance, initial_step,
                min_step, max_steps);
#define PK_EVALUATE_FIELD(point, derivative) \
  pk_field_value(field, center_count, center_stride, coefficients, (point), (derivative))
  PK_RK45_INTEGRATE_PARTICLE(controller, x, PK_EVALUATE_FIELD);
#undef PK_EVALUATE_FIELD
  positions[i] = x[0];
  positions[particle_stride + i] = x[1];
  positions[2 * (size_t)particle_stride + i] = x[2];
  stats[4 * (size_t)i] = controller.accepted_steps;
  stats[4 * (size_t)i + 1] = controller.rejected_steps;
  stats[4 * (size_t)i + 2] = controller.rhs_evaluations;
  stats[4 * (size_t)i + 3] = controller.status;
}
