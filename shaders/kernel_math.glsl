// The GLSL mirror of backends/common/kernel_math.h, which GLSL cannot include. Every function
// here carries the name of the C function it mirrors and performs the same operations in the same
// order; the constants come from kernel_constants.glsl, generated at build time from the C header's
// PK_KERNEL_DOUBLE_CONSTANTS / PK_KERNEL_WORD_CONSTANTS lists, so both sides use identical bits.
//
// Requires: #version 450 and shaderFloat64 (GLSL 4.00 doubles). No 64-bit integers: bit
// manipulations work on the two 32-bit words that unpackDouble2x32 returns (x: low, y: high).
#ifndef POSEKIT_KERNEL_MATH_GLSL
#define POSEKIT_KERNEL_MATH_GLSL

#include "kernel_constants.glsl"

// ------------------------------------------------------------------------------------------------
// Section 1: language glue
// ------------------------------------------------------------------------------------------------

// Mirrors pk_is_finite: tested on the exponent bits, so no compiler assumption about NaN or
// infinity can fold it away.
bool pk_is_finite(double x) { return ((unpackDouble2x32(x).y >> 20) & 0x7ffu) != 0x7ffu; }

bool pk_is_finite(dvec3 v) { return pk_is_finite(v.x) && pk_is_finite(v.y) && pk_is_finite(v.z); }

// ------------------------------------------------------------------------------------------------
// Section 2: natural logarithm (GLSL has no double-precision log)
// ------------------------------------------------------------------------------------------------

// Mirrors pk_log: fdlibm's e_log.c method (see the notice in kernel_math.h), for positive normal
// doubles, within 1 ulp. The 64-bit integer steps of the C code act on the high word only:
//   bits += (ONE_HIGH - SQRT_HALF_HIGH) << 32    adds to the high word (no carry out of it for
//                                                positive finite x);
//   k = double(bits >> 52 | TWO_POW_52_HIGH << 32) - MAGIC
//                                                bits >> 52 is the high word >> 20;
//   bits = (bits & (2^52 - 1)) + (SQRT_HALF_HIGH << 32)
//                                                keeps the low word and the high word's 20
//                                                mantissa bits.
double pk_log(double x) {
  const uvec2 words = unpackDouble2x32(x);
  uint high = words.y + (uint(PK_LOG_ONE_HIGH_WORD) - uint(PK_LOG_SQRT_HALF_HIGH_WORD));
  const double k = packDouble2x32(uvec2(high >> 20, uint(PK_LOG_TWO_POW_52_HIGH_WORD))) -
                   PK_LOG_EXPONENT_BIAS_MAGIC;
  high = (high & 0xfffffu) + uint(PK_LOG_SQRT_HALF_HIGH_WORD);
  const double f = packDouble2x32(uvec2(words.x, high)) - 1.0LF;
  const double half_f_squared = 0.5LF * f * f;
  const double s = f / (2.0LF + f);
  const double z = s * s;
  const double w = z * z;
  const double even = w * (PK_LOG_LG2 + w * (PK_LOG_LG4 + w * PK_LOG_LG6));
  const double odd = z * (PK_LOG_LG1 + w * (PK_LOG_LG3 + w * (PK_LOG_LG5 + w * PK_LOG_LG7)));
  const double r = odd + even;
  return s * (half_f_squared + r) + k * PK_LOG_LN2_LO - half_f_squared + f + k * PK_LOG_LN2_HI;
}

// ------------------------------------------------------------------------------------------------
// Section 3: RBF kernel and polynomial basis
// ------------------------------------------------------------------------------------------------

// Mirrors pk_squared_distance, from the difference point - center; the order of the additions is
// part of the definition (no dot(), which may sum in another order).
double pk_squared_distance(dvec4 d) { return d.x * d.x + d.y * d.y + d.z * d.z + d.w * d.w; }

// Mirrors pk_phi_from_squared_distance: phi = 0.5 r2 ln(r2 + DBL_MIN), 0 at r2 = 0 without a
// branch.
double pk_phi_from_squared_distance(double r2) { return 0.5LF * r2 * pk_log(r2 + PK_DBL_MIN); }

// Mirrors pk_polynomial_basis, one term at a time: term `index` (0..14) at p = (x, y, z, t) in the
// order 1, x, y, z, t, x^2, xy, xz, xt, y^2, yz, yt, z^2, zt, t^2.
double pk_polynomial_term(uint index, dvec4 p) {
  switch (index) {
    case 0u: return 1.0LF;
    case 1u: return p.x;
    case 2u: return p.y;
    case 3u: return p.z;
    case 4u: return p.w;
    case 5u: return p.x * p.x;
    case 6u: return p.x * p.y;
    case 7u: return p.x * p.z;
    case 8u: return p.x * p.w;
    case 9u: return p.y * p.y;
    case 10u: return p.y * p.z;
    case 11u: return p.y * p.w;
    case 12u: return p.z * p.z;
    case 13u: return p.z * p.w;
    default: return p.w * p.w;
  }
}

// ------------------------------------------------------------------------------------------------
// Section 4: Dormand-Prince 5(4) with adaptive steps
// ------------------------------------------------------------------------------------------------

// Mirrors struct pk_rk45_controller.
struct pk_rk45_controller {
  double t;
  double t_end;
  double direction;
  double h;
  double relative_tolerance;
  double absolute_tolerance;
  double min_step;
  int max_steps;
  int accepted_steps;
  int rejected_steps;
  int rhs_evaluations;
  int status;
  bool previous_rejected;
  bool reaches_end;
};

// Mirrors pk_rk45_begin.
void pk_rk45_begin(inout pk_rk45_controller c, double t_begin, double t_end,
                   double relative_tolerance, double absolute_tolerance, double initial_step,
                   double min_step, int max_steps) {
  c.t = t_begin;
  c.t_end = t_end;
  c.direction = t_end >= t_begin ? 1.0LF : -1.0LF;
  c.h = initial_step;
  c.relative_tolerance = relative_tolerance;
  c.absolute_tolerance = absolute_tolerance;
  c.min_step = min_step;
  c.max_steps = max_steps;
  c.accepted_steps = 0;
  c.rejected_steps = 0;
  c.rhs_evaluations = 0;
  c.status = t_end == t_begin ? PK_RK45_OK : PK_RK45_RUNNING;
  c.previous_rejected = false;
  c.reaches_end = false;
}

// Mirrors pk_rk45_record_first_evaluation.
void pk_rk45_record_first_evaluation(inout pk_rk45_controller c, dvec3 k1) {
  c.rhs_evaluations = 1;
  if (!pk_is_finite(k1)) c.status = PK_RK45_NON_FINITE;
}

// Mirrors pk_rk45_trial_step.
double pk_rk45_trial_step(inout pk_rk45_controller c) {
  const double remaining = (c.t_end - c.t) * c.direction;
  double h = c.h;
  c.reaches_end = h * PK_RK45_END_STRETCH >= remaining;
  if (c.reaches_end) h = remaining;
  return c.direction * h;
}

// Mirrors pk_rk45_stage_time for stages 2..7 (stage 1 is at c.t itself).
double pk_rk45_stage_time(pk_rk45_controller c, double fraction, double step) {
  return c.t + fraction * step;
}

// Mirrors pk_rk45_stage_position, one stage per function: x + step * (sum_j A_sj k_j), the sum
// in the C code's order, componentwise.
dvec3 pk_rk45_stage2_position(double step, dvec3 x, dvec3 k1) {
  return x + step * (PK_DP_A21 * k1);
}
dvec3 pk_rk45_stage3_position(double step, dvec3 x, dvec3 k1, dvec3 k2) {
  return x + step * (PK_DP_A31 * k1 + PK_DP_A32 * k2);
}
dvec3 pk_rk45_stage4_position(double step, dvec3 x, dvec3 k1, dvec3 k2, dvec3 k3) {
  return x + step * (PK_DP_A41 * k1 + PK_DP_A42 * k2 + PK_DP_A43 * k3);
}
dvec3 pk_rk45_stage5_position(double step, dvec3 x, dvec3 k1, dvec3 k2, dvec3 k3, dvec3 k4) {
  return x + step * (PK_DP_A51 * k1 + PK_DP_A52 * k2 + PK_DP_A53 * k3 + PK_DP_A54 * k4);
}
dvec3 pk_rk45_stage6_position(double step, dvec3 x, dvec3 k1, dvec3 k2, dvec3 k3, dvec3 k4,
                              dvec3 k5) {
  return x + step * (PK_DP_A61 * k1 + PK_DP_A62 * k2 + PK_DP_A63 * k3 + PK_DP_A64 * k4 +
                     PK_DP_A65 * k5);
}
// Stage 7: the fifth-order solution.
dvec3 pk_rk45_stage7_position(double step, dvec3 x, dvec3 k1, dvec3 k3, dvec3 k4, dvec3 k5,
                              dvec3 k6) {
  return x + step * (PK_DP_B1 * k1 + PK_DP_B3 * k3 + PK_DP_B4 * k4 + PK_DP_B5 * k5 +
                     PK_DP_B6 * k6);
}

// Mirrors pk_rk45_error_norm (k2 has no error weight).
double pk_rk45_error_norm(double step, dvec3 x, dvec3 x_new, dvec3 k1, dvec3 k3, dvec3 k4,
                          dvec3 k5, dvec3 k6, dvec3 k7, double relative_tolerance,
                          double absolute_tolerance) {
  const dvec3 error = step * (PK_DP_E1 * k1 + PK_DP_E3 * k3 + PK_DP_E4 * k4 + PK_DP_E5 * k5 +
                              PK_DP_E6 * k6 + PK_DP_E7 * k7);
  const dvec3 a = abs(x);
  const dvec3 b = abs(x_new);
  const dvec3 scale = absolute_tolerance + relative_tolerance * mix(b, a, greaterThan(a, b));
  const dvec3 ratio = error / scale;
  double sum = 0.0LF;
  sum += ratio.x * ratio.x;
  sum += ratio.y * ratio.y;
  sum += ratio.z * ratio.z;
  return sqrt(sum / 3.0LF);
}

// The rounding error of the product p = a * b (p + error = a b exactly), by Dekker's splitting of
// each factor into two 26-bit halves: Vulkan does not require fma() to be fused (lavapipe's is
// not), so fma(a, b, -p) would not recover it. `precise` keeps the compiler from reassociating or
// fusing these operations. Needs |a|, |b| well inside the double range.
double pk_high_half(double a) {
  precise const double scaled = 134217729.0LF * a;  // 2^27 + 1
  precise const double high = scaled - (scaled - a);
  return high;
}
double pk_product_error(double a, double b, double p) {
  precise const double a_high = pk_high_half(a);
  precise const double a_low = a - a_high;
  precise const double b_high = pk_high_half(b);
  precise const double b_low = b - b_high;
  precise const double error =
      ((a_high * b_high - p) + a_high * b_low + a_low * b_high) + a_low * b_low;
  return error;
}

// (high + low) * y as a new unevaluated sum high + low.
void pk_multiply_unevaluated_sum(inout double high, inout double low, double y) {
  precise const double product = high * y;
  precise const double error = pk_product_error(high, y, product);
  precise const double carried = error + low * y;
  high = product;
  low = carried;
}

// The relative correction of one Newton step towards y = err^(-1/5): (1 - err y^5) / 5, so that
// y (1 + correction) is the next approximation. The product err y^5 is kept as an unevaluated sum
// high + low, so that 1 - err y^5 is exact to far below an ulp near convergence.
double pk_fifth_root_newton_correction(double err, double y) {
  double high = err;
  double low = 0.0LF;
  pk_multiply_unevaluated_sum(high, low, y);
  pk_multiply_unevaluated_sum(high, low, y);
  pk_multiply_unevaluated_sum(high, low, y);
  pk_multiply_unevaluated_sum(high, low, y);
  pk_multiply_unevaluated_sum(high, low, y);
  precise const double defect = (1.0LF - high) - low;
  return defect / 5.0LF;
}

// pow(err, PK_RK45_ERROR_EXPONENT) for the step factors, as the C code's PK_POW computes it
// (within an ulp); GLSL has no double-precision pow. Only 1e-6 <= err <= 1e4 needs a value:
// below, SAFETY * err^-0.2 > 14 is clamped to MAX_FACTOR = 10 and above, < 0.15 to
// MIN_FACTOR = 0.2, so those ranges return values on the right side of the clamps. Inside,
// y = err^(-1/5) by Newton's method on y^-5 = err from a single-precision start (relative error
// e -> 3 e^2 per step; three steps reach rounding from e < 1e-3). The last step also corrects for
// the exponent: the double -0.2 is -1/5 - 1.1102230246251565e-17, so err^-0.2 =
// err^(-1/5) (1 - 1.11e-17 ln err); both corrections are added in one rounding.
double pk_pow_error_exponent(double err) {
  if (err < 1e-6LF) return 1e300LF;
  if (err > 1e4LF) return 0.0LF;
  double y = double(pow(float(err), -0.2));
  y += y * pk_fifth_root_newton_correction(err, y);
  y += y * pk_fifth_root_newton_correction(err, y);
  const double exponent_correction = -1.1102230246251565e-17LF * pk_log(err);
  return y + y * (pk_fifth_root_newton_correction(err, y) + exponent_correction);
}

// Mirrors pk_rk45_accept_factor (0 <= err <= 1).
double pk_rk45_accept_factor(double err, bool previous_rejected) {
  double factor = PK_RK45_MAX_FACTOR;
  if (err > 0.0LF) {
    factor = PK_RK45_SAFETY * pk_pow_error_exponent(err);
    if (factor > PK_RK45_MAX_FACTOR) factor = PK_RK45_MAX_FACTOR;
  }
  if (previous_rejected && factor > 1.0LF) factor = 1.0LF;
  return factor;
}

// Mirrors pk_rk45_reject_factor (err > 1).
double pk_rk45_reject_factor(double err) {
  const double factor = PK_RK45_SAFETY * pk_pow_error_exponent(err);
  return factor < PK_RK45_MIN_FACTOR ? PK_RK45_MIN_FACTOR : factor;
}

// Mirrors pk_rk45_finish_step: all 7 stages known, x_new the stage-7 position. On acceptance
// moves x to x_new and k7 into k1 (first same as last).
void pk_rk45_finish_step(inout pk_rk45_controller c, double step, inout dvec3 x, inout dvec3 k1,
                         dvec3 k3, dvec3 k4, dvec3 k5, dvec3 k6, dvec3 k7, dvec3 x_new) {
  c.rhs_evaluations += PK_DP_STAGES - 1;
  if (!pk_is_finite(x_new)) {
    c.status = PK_RK45_NON_FINITE;
    return;
  }
  const double err = pk_rk45_error_norm(step, x, x_new, k1, k3, k4, k5, k6, k7,
                                        c.relative_tolerance, c.absolute_tolerance);
  if (!pk_is_finite(err)) {
    c.status = PK_RK45_NON_FINITE;
    return;
  }
  if (err <= 1.0LF) {
    c.accepted_steps += 1;
    x = x_new;
    k1 = k7;
    if (c.reaches_end) {
      c.t = c.t_end;
      c.status = PK_RK45_OK;
    } else {
      c.t += step;
      c.h = abs(step) * pk_rk45_accept_factor(err, c.previous_rejected);
    }
    c.previous_rejected = false;
  } else {
    c.rejected_steps += 1;
    c.h = abs(step) * pk_rk45_reject_factor(err);
    c.previous_rejected = true;
    if (c.h < c.min_step) c.status = PK_RK45_STEP_UNDERFLOW;
  }
  if (c.status == PK_RK45_RUNNING && c.accepted_steps + c.rejected_steps >= c.max_steps) {
    c.status = PK_RK45_MAX_STEPS;
  }
}

#endif  // POSEKIT_KERNEL_MATH_GLSL
