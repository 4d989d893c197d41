/* posekit kernel math: the formulas every compute backend shares, defined once.
 *
 * Included by host C and C++, by OpenCL C (the .cl sources embed it) and by CUDA (host and device
 * code). Everything is a plain C99-style inline function or a macro with the prefix pk_ / PK_, so
 * the same text compiles in all four languages; the few language-specific pieces (bit casts, the
 * function qualifier) sit in the first section. Nothing here allocates, branches per element in a
 * hot loop or calls a library function that would stop a compiler from vectorizing a loop over
 * centers.
 *
 * Contents:
 *   1. language glue: PK_INLINE, pk_u64, bit casts, pk_is_finite
 *   2. the natural logarithm pk_log (vectorizable, <= 1 ulp over positive normal doubles)
 *   3. the RBF kernel phi from the squared distance, and the polynomial basis of R^4
 *   4. the Dormand-Prince 5(4) tableau, the step-size control and a per-particle driver
 *   5. PK_KERNEL_DOUBLE_CONSTANTS / PK_KERNEL_WORD_CONSTANTS: every constant in one list, so that a
 *      generator can emit them for GLSL (which cannot include this file)
 *
 * Every backend evaluates the same formulas in the same order and takes its step decisions with the
 * same constants; results still differ in the last bits where a backend sums in another order or
 * contracts a*b+c into a fused multiply-add.
 */
#ifndef POSEKIT_KERNEL_MATH_H
#define POSEKIT_KERNEL_MATH_H

/* ---------------------------------------------------------------------------------------------- */
/* 1. Language glue                                                                               */
/* ---------------------------------------------------------------------------------------------- */

#if defined(__OPENCL_VERSION__)

#if defined(cl_khr_fp64) && (!defined(__OPENCL_C_VERSION__) || __OPENCL_C_VERSION__ < 300)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif
#if defined(__OPENCL_C_VERSION__) && __OPENCL_C_VERSION__ >= 120
#define PK_INLINE static inline
#else
#define PK_INLINE inline
#endif
typedef ulong pk_u64;
PK_INLINE pk_u64 pk_bits_of(double x) { return as_ulong(x); }
PK_INLINE double pk_double_from_bits(pk_u64 bits) { return as_double(bits); }
#define PK_SQRT(x) sqrt(x)
#define PK_POW(x, y) pow((x), (y))
#define PK_FABS(x) fabs(x)

#elif defined(__CUDACC__)

#define PK_INLINE static __host__ __device__ inline
typedef unsigned long long pk_u64;
#if defined(__CUDA_ARCH__)
PK_INLINE pk_u64 pk_bits_of(double x) { return (pk_u64)__double_as_longlong(x); }
PK_INLINE double pk_double_from_bits(pk_u64 bits) { return __longlong_as_double((long long)bits); }
#else
#include <cstring>
PK_INLINE pk_u64 pk_bits_of(double x) {
  pk_u64 bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}
PK_INLINE double pk_double_from_bits(pk_u64 bits) {
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}
#endif
#include <cmath>
#define PK_SQRT(x) sqrt(x)
#define PK_POW(x, y) pow((x), (y))
#define PK_FABS(x) fabs(x)

#else /* host C or C++ */

#if defined(__cplusplus)
#include <cmath>
#include <cstdint>
#include <cstring>
#define PK_MEMCPY std::memcpy
#define PK_SQRT(x) std::sqrt(x)
#define PK_POW(x, y) std::pow((x), (y))
#define PK_FABS(x) std::fabs(x)
typedef std::uint64_t pk_u64;
#else
#include <math.h>
#include <stdint.h>
#include <string.h>
#define PK_MEMCPY memcpy
#define PK_SQRT(x) sqrt(x)
#define PK_POW(x, y) pow((x), (y))
#define PK_FABS(x) fabs(x)
typedef uint64_t pk_u64;
#endif
/* always_inline: a call left inside a loop over centers would keep it from being vectorized. */
#if defined(__GNUC__)
#define PK_INLINE static inline __attribute__((always_inline))
#else
#define PK_INLINE static inline
#endif
/* memcpy of 8 bytes is the portable bit cast; compilers turn it into a register move, also in
 * vectorized loops. */
PK_INLINE pk_u64 pk_bits_of(double x) {
  pk_u64 bits;
  PK_MEMCPY(&bits, &x, sizeof bits);
  return bits;
}
PK_INLINE double pk_double_from_bits(pk_u64 bits) {
  double x;
  PK_MEMCPY(&x, &bits, sizeof x);
  return x;
}

#endif

/* True for every double except +-inf and NaN. Tested on the exponent bits so that no compiler
 * option (-ffinite-math-only) can fold it away. */
PK_INLINE int pk_is_finite(double x) {
  return ((pk_bits_of(x) >> 52) & 0x7ffu) != 0x7ffu;
}

/* ---------------------------------------------------------------------------------------------- */
/* 2. Natural logarithm                                                                           */
/* ---------------------------------------------------------------------------------------------- */

/* pk_log(x) = ln x for positive normal x (DBL_MIN <= x <= DBL_MAX), within 1 ulp of the exact value
 * (0.76 ulp measured over 2e7 log-uniform samples in 1e-300..1e300 and near 1).
 *
 * Method and coefficients from fdlibm's e_log.c, whose notice is:
 *   Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved.
 *   Developed at SunSoft, a Sun Microsystems, Inc. business.
 *   Permission to use, copy, modify, and distribute this software is freely granted, provided
 *   that this notice is preserved.
 * Write x = 2^k * m with m in [sqrt(2)/2, sqrt(2)) by integer arithmetic on the bits (no branch:
 * adding 0x3ff00000 - 0x3fe6a09e to the high word carries into the exponent exactly when the
 * mantissa is >= sqrt(2)), then ln m = 2 atanh(s) with s = f / (2 + f), f = m - 1, through a
 * degree-14 minimax polynomial in s, and ln x = k ln2 + ln m with ln2 split into a high part (exact
 * in k * ln2_hi) and a low part. k is turned into a double by the 2^52 trick instead of an
 * int64 -> double conversion, which AVX2 lacks.
 *
 * Domain: only positive normal doubles are handled. For +inf and NaN it returns a finite value
 * (about 709.8) instead of inf / NaN; zero, subnormals and negative numbers give meaningless
 * results. pk_phi_from_squared_distance never passes such values (it adds DBL_MIN to a square and
 * multiplies the logarithm by that square, which carries inf and NaN through). */
#define PK_LOG_LN2_HI 6.93147180369123816490e-01 /* 0x3fe62e42fee00000 */
#define PK_LOG_LN2_LO 1.90821492927058770002e-10 /* 0x3dea39ef35793c76 */
#define PK_LOG_LG1 6.666666666666735130e-01      /* 0x3fe5555555555593 */
#define PK_LOG_LG2 3.999999999940941908e-01      /* 0x3fd999999997fa04 */
#define PK_LOG_LG3 2.857142874366239149e-01      /* 0x3fd2492494229359 */
#define PK_LOG_LG4 2.222219843214978396e-01      /* 0x3fcc71c51d8e78af */
#define PK_LOG_LG5 1.818357216161805012e-01      /* 0x3fc7466496cb03de */
#define PK_LOG_LG6 1.531383769920937332e-01      /* 0x3fc39a09d078c69f */
#define PK_LOG_LG7 1.479819860511658591e-01      /* 0x3fc2f112df3e5244 */
/* 2^52 + 1023: subtracting it from the double whose low mantissa bits hold the biased exponent
 * leaves the unbiased exponent k. */
#define PK_LOG_EXPONENT_BIAS_MAGIC 4503599627371519.0
/* High 32-bit words: of 1.0, of sqrt(2)/2 (rounded down), and of 2^52. */
#define PK_LOG_ONE_HIGH_WORD 0x3ff00000u
#define PK_LOG_SQRT_HALF_HIGH_WORD 0x3fe6a09eu
#define PK_LOG_TWO_POW_52_HIGH_WORD 0x43300000u

/* The body of pk_log for a floating type and the unsigned integer type of its bits, with the casts
 * between them: written once, defined below for double and, lane by lane, for OpenCL's vectors of
 * doubles (kernels/opencl/vector_math.cl), which must compute the same operations in the same
 * order. */
#define PK_DEFINE_LOG(name, real_t, bits_t, bits_of, real_from_bits)                              \
  PK_INLINE real_t name(real_t x) {                                                               \
    bits_t bits = bits_of(x);                                                                     \
    bits += (pk_u64)(PK_LOG_ONE_HIGH_WORD - PK_LOG_SQRT_HALF_HIGH_WORD) << 32;                    \
    const real_t k = real_from_bits((bits >> 52) | ((pk_u64)PK_LOG_TWO_POW_52_HIGH_WORD << 32)) - \
                     PK_LOG_EXPONENT_BIAS_MAGIC;                                                  \
    bits = (bits & (((pk_u64)1 << 52) - 1)) + ((pk_u64)PK_LOG_SQRT_HALF_HIGH_WORD << 32);         \
    const real_t f = real_from_bits(bits) - 1.0;                                                  \
    const real_t half_f_squared = 0.5 * f * f;                                                    \
    const real_t s = f / (2.0 + f);                                                               \
    const real_t z = s * s;                                                                       \
    const real_t w = z * z;                                                                       \
    const real_t even = w * (PK_LOG_LG2 + w * (PK_LOG_LG4 + w * PK_LOG_LG6));                     \
    const real_t odd = z * (PK_LOG_LG1 + w * (PK_LOG_LG3 + w * (PK_LOG_LG5 + w * PK_LOG_LG7)));   \
    const real_t r = odd + even;                                                                  \
    return s * (half_f_squared + r) + k * PK_LOG_LN2_LO - half_f_squared + f + k * PK_LOG_LN2_HI; \
  }

PK_DEFINE_LOG(pk_log, double, pk_u64, pk_bits_of, pk_double_from_bits)

/* ---------------------------------------------------------------------------------------------- */
/* 3. RBF kernel and polynomial basis                                                             */
/* ---------------------------------------------------------------------------------------------- */

/* Smallest positive normal double (DBL_MIN), spelled out so that no language needs <float.h>. */
#define PK_DBL_MIN 2.2250738585072014e-308

/* Squared distance between two points of R^4 from coordinate differences. Differences keep close
 * pairs accurate; |a|^2 + |b|^2 - 2 a.b would cancel catastrophically. The order of the additions
 * is part of the definition. */
#define PK_DEFINE_SQUARED_DISTANCE(name, real_t)                  \
  PK_INLINE real_t name(real_t dx, real_t dy, real_t dz, real_t dt) { \
    return dx * dx + dy * dy + dz * dz + dt * dt;                     \
  }
PK_DEFINE_SQUARED_DISTANCE(pk_squared_distance, double)

/* phi(r) = r^2 ln r written in r2 = r^2: phi = 0.5 r2 ln r2. Adding DBL_MIN keeps the logarithm's
 * argument a positive normal number, so r2 = 0 gives 0.5 * 0 * ln(DBL_MIN) = 0 (as -0.0) without a
 * branch; for r2 >= 2^-969 the addition does not change r2 at all. r2 = inf gives inf and NaN gives
 * NaN. */
#define PK_DEFINE_PHI_FROM_SQUARED_DISTANCE(name, real_t, log) \
  PK_INLINE real_t name(real_t r2) {                            \
    return 0.5 * r2 * log(r2 + PK_DBL_MIN);                     \
  }
PK_DEFINE_PHI_FROM_SQUARED_DISTANCE(pk_phi_from_squared_distance, double, pk_log)

/* The quadratic polynomial basis of R^4: 15 monomials of (x, y, z, t) in this order (the rows of
 * posekit::RbfPolynomial and the last 15 columns of an assembled RBF block):
 *
 *   index  0  1  2  3  4  5    6    7    8    9    10   11   12   13   14
 *   term   1  x  y  z  t  x^2  x*y  x*z  x*t  y^2  y*z  y*t  z^2  z*t  t^2
 *
 * Constant, linear terms, then the upper triangle of the products row by row. */
#define PK_POLYNOMIAL_TERMS 15

/* Writes the 15 basis values at (x, y, z, t) into basis[0..14] (private memory in OpenCL). */
PK_INLINE void pk_polynomial_basis(double x, double y, double z, double t, double* basis) {
  basis[0] = 1.0;
  basis[1] = x;
  basis[2] = y;
  basis[3] = z;
  basis[4] = t;
  basis[5] = x * x;
  basis[6] = x * y;
  basis[7] = x * z;
  basis[8] = x * t;
  basis[9] = y * y;
  basis[10] = y * z;
  basis[11] = y * t;
  basis[12] = z * z;
  basis[13] = z * t;
  basis[14] = t * t;
}

/* sum_k coefficients[k] * basis_k(x, y, z, t) for one output component; coefficients points at
 * the 15 values of that component (one column of the column-major 15 by 3 RbfPolynomial). */
PK_INLINE double pk_polynomial_value(const double* coefficients, double x, double y, double z,
                                     double t) {
  double basis[PK_POLYNOMIAL_TERMS];
  double sum = 0.0;
  int k;
  pk_polynomial_basis(x, y, z, t, basis);
  for (k = 0; k < PK_POLYNOMIAL_TERMS; ++k) sum += coefficients[k] * basis[k];
  return sum;
}

/* ---------------------------------------------------------------------------------------------- */
/* 4. Dormand-Prince 5(4) with adaptive steps                                                     */
/* ---------------------------------------------------------------------------------------------- */

/* The tableau of Dormand & Prince (1980), as in Hairer, Norsett & Wanner, Solving ODEs I,
 * table II.5.2. Seven stages; the seventh is evaluated at the fifth-order solution, so an accepted
 * step hands it on as the first stage of the next step ("first same as last"): 6 new evaluations
 * per step. */
#define PK_DP_STAGES 7
#define PK_DP_C2 (1.0 / 5.0)
#define PK_DP_C3 (3.0 / 10.0)
#define PK_DP_C4 (4.0 / 5.0)
#define PK_DP_C5 (8.0 / 9.0)
#define PK_DP_C6 1.0
#define PK_DP_C7 1.0
#define PK_DP_A21 (1.0 / 5.0)
#define PK_DP_A31 (3.0 / 40.0)
#define PK_DP_A32 (9.0 / 40.0)
#define PK_DP_A41 (44.0 / 45.0)
#define PK_DP_A42 (-56.0 / 15.0)
#define PK_DP_A43 (32.0 / 9.0)
#define PK_DP_A51 (19372.0 / 6561.0)
#define PK_DP_A52 (-25360.0 / 2187.0)
#define PK_DP_A53 (64448.0 / 6561.0)
#define PK_DP_A54 (-212.0 / 729.0)
#define PK_DP_A61 (9017.0 / 3168.0)
#define PK_DP_A62 (-355.0 / 33.0)
#define PK_DP_A63 (46732.0 / 5247.0)
#define PK_DP_A64 (49.0 / 176.0)
#define PK_DP_A65 (-5103.0 / 18656.0)
/* Fifth-order weights (also row 7 of A; B2 = B7 = 0). */
#define PK_DP_B1 (35.0 / 384.0)
#define PK_DP_B3 (500.0 / 1113.0)
#define PK_DP_B4 (125.0 / 192.0)
#define PK_DP_B5 (-2187.0 / 6784.0)
#define PK_DP_B6 (11.0 / 84.0)
/* Error weights E = B(5th order) - B(4th order); E2 = 0. */
#define PK_DP_E1 (71.0 / 57600.0)
#define PK_DP_E3 (-71.0 / 16695.0)
#define PK_DP_E4 (71.0 / 1920.0)
#define PK_DP_E5 (-17253.0 / 339200.0)
#define PK_DP_E6 (22.0 / 525.0)
#define PK_DP_E7 (-1.0 / 40.0)

/* Step-size control (Hairer, Norsett & Wanner, section II.4):
 *   error norm  err = sqrt( (1/3) sum_i (e_i / (atol + rtol * max(|x_i|, |x_new_i|)))^2 ),
 *               e = h * sum_j E_j k_j, over the 3 components of a particle;
 *   a step is accepted when err <= 1;
 *   next step   h * clamp(SAFETY * err^(-1/5), MIN_FACTOR, MAX_FACTOR), err = 0 giving MAX_FACTOR,
 *               and never growing right after a rejected attempt;
 *   end of the interval: a step that would leave less than 1% of itself is stretched to reach the
 *               end exactly.
 * A step proposed after a rejection below min_step ends the particle with step_underflow; a
 * non-finite derivative, position or error norm ends it with non_finite; max_steps attempts
 * (accepted plus rejected) end it with max_steps. A particle that fails keeps the position it had
 * reached. */
#define PK_RK45_SAFETY 0.9
#define PK_RK45_MIN_FACTOR 0.2
#define PK_RK45_MAX_FACTOR 10.0
#define PK_RK45_ERROR_EXPONENT (-0.2)
#define PK_RK45_END_STRETCH 1.01

/* Particle states, equal to posekit::Rk45Status, plus one for a particle still moving. */
#define PK_RK45_RUNNING (-1)
#define PK_RK45_OK 0
#define PK_RK45_MAX_STEPS 1
#define PK_RK45_STEP_UNDERFLOW 2
#define PK_RK45_NON_FINITE 3

/* The adaptive state of one particle. Positions and stage derivatives live with the caller:
 * x[3] and k[21], k holding the 7 stage derivatives one after the other (k[3*s + i]). */
typedef struct pk_rk45_controller {
  double t;           /* current time */
  double t_end;       /* time to reach */
  double direction;   /* +1 forward, -1 backward */
  double h;           /* magnitude of the next trial step (> 0) */
  double relative_tolerance;
  double absolute_tolerance;
  double min_step;
  int max_steps;
  int accepted_steps;
  int rejected_steps;
  int rhs_evaluations;
  int status;             /* PK_RK45_RUNNING or a final state */
  int previous_rejected;  /* the last attempt was rejected: do not grow the step */
  int reaches_end;        /* the current trial step ends exactly at t_end */
} pk_rk45_controller;

/* Starts a particle at t_begin. Arguments are checked by the host before any kernel runs. */
PK_INLINE void pk_rk45_begin(pk_rk45_controller* c, double t_begin, double t_end,
                             double relative_tolerance, double absolute_tolerance,
                             double initial_step, double min_step, int max_steps) {
  c->t = t_begin;
  c->t_end = t_end;
  c->direction = t_end >= t_begin ? 1.0 : -1.0;
  c->h = initial_step;
  c->relative_tolerance = relative_tolerance;
  c->absolute_tolerance = absolute_tolerance;
  c->min_step = min_step;
  c->max_steps = max_steps;
  c->accepted_steps = 0;
  c->rejected_steps = 0;
  c->rhs_evaluations = 0;
  c->status = t_end == t_begin ? PK_RK45_OK : PK_RK45_RUNNING;
  c->previous_rejected = 0;
  c->reaches_end = 0;
}

/* Records the first evaluation k1 = f(x, t_begin), k pointing at its 3 values. */
PK_INLINE void pk_rk45_record_first_evaluation(pk_rk45_controller* c, const double* k1) {
  c->rhs_evaluations = 1;
  if (!(pk_is_finite(k1[0]) && pk_is_finite(k1[1]) && pk_is_finite(k1[2]))) {
    c->status = PK_RK45_NON_FINITE;
  }
}

/* The signed step of the next attempt: the controller's step, shortened or stretched (by at most
 * PK_RK45_END_STRETCH) to end exactly at t_end. */
PK_INLINE double pk_rk45_trial_step(pk_rk45_controller* c) {
  const double remaining = (c->t_end - c->t) * c->direction;
  double h = c->h;
  c->reaches_end = h * PK_RK45_END_STRETCH >= remaining;
  if (c->reaches_end) h = remaining;
  return c->direction * h;
}

/* Time of stage s (1..7) of a step of signed length `step`. */
PK_INLINE double pk_rk45_stage_time(const pk_rk45_controller* c, int stage, double step) {
  double fraction;
  switch (stage) {
    case 1: fraction = 0.0; break;
    case 2: fraction = PK_DP_C2; break;
    case 3: fraction = PK_DP_C3; break;
    case 4: fraction = PK_DP_C4; break;
    case 5: fraction = PK_DP_C5; break;
    case 6: fraction = PK_DP_C6; break;
    default: fraction = PK_DP_C7; break;
  }
  return c->t + fraction * step;
}

/* Position y[3] at which stage s (2..7) evaluates the field: x + step * sum_{j<s} A_sj k_j, using
 * the derivatives k_1..k_{s-1} already in k. Stage 7 gives the fifth-order solution. */
PK_INLINE void pk_rk45_stage_position(int stage, double step, const double* x, const double* k,
                                      double* y) {
  int i;
  for (i = 0; i < 3; ++i) {
    double increment;
    switch (stage) {
      case 2: increment = PK_DP_A21 * k[i]; break;
      case 3: increment = PK_DP_A31 * k[i] + PK_DP_A32 * k[3 + i]; break;
      case 4: increment = PK_DP_A41 * k[i] + PK_DP_A42 * k[3 + i] + PK_DP_A43 * k[6 + i]; break;
      case 5:
        increment = PK_DP_A51 * k[i] + PK_DP_A52 * k[3 + i] + PK_DP_A53 * k[6 + i] +
                    PK_DP_A54 * k[9 + i];
        break;
      case 6:
        increment = PK_DP_A61 * k[i] + PK_DP_A62 * k[3 + i] + PK_DP_A63 * k[6 + i] +
                    PK_DP_A64 * k[9 + i] + PK_DP_A65 * k[12 + i];
        break;
      default:
        increment = PK_DP_B1 * k[i] + PK_DP_B3 * k[6 + i] + PK_DP_B4 * k[9 + i] +
                    PK_DP_B5 * k[12 + i] + PK_DP_B6 * k[15 + i];
        break;
    }
    y[i] = x[i] + step * increment;
  }
}

/* The error norm of a step (see the step-size control above); k holds all 7 stages. */
PK_INLINE double pk_rk45_error_norm(double step, const double* x, const double* x_new,
                                    const double* k, double relative_tolerance,
                                    double absolute_tolerance) {
  double sum = 0.0;
  int i;
  for (i = 0; i < 3; ++i) {
    const double error = step * (PK_DP_E1 * k[i] + PK_DP_E3 * k[6 + i] + PK_DP_E4 * k[9 + i] +
                                 PK_DP_E5 * k[12 + i] + PK_DP_E6 * k[15 + i] +
                                 PK_DP_E7 * k[18 + i]);
    const double a = PK_FABS(x[i]);
    const double b = PK_FABS(x_new[i]);
    const double scale = absolute_tolerance + relative_tolerance * (a > b ? a : b);
    const double ratio = error / scale;
    sum += ratio * ratio;
  }
  return PK_SQRT(sum / 3.0);
}

/* Factor on the step size after an accepted step with error norm err (0 <= err <= 1). */
PK_INLINE double pk_rk45_accept_factor(double err, int previous_rejected) {
  double factor = PK_RK45_MAX_FACTOR;
  if (err > 0.0) {
    factor = PK_RK45_SAFETY * PK_POW(err, PK_RK45_ERROR_EXPONENT);
    if (factor > PK_RK45_MAX_FACTOR) factor = PK_RK45_MAX_FACTOR;
  }
  if (previous_rejected && factor > 1.0) factor = 1.0;
  return factor;
}

/* Factor on the step size after a rejected step with error norm err (> 1). */
PK_INLINE double pk_rk45_reject_factor(double err) {
  const double factor = PK_RK45_SAFETY * PK_POW(err, PK_RK45_ERROR_EXPONENT);
  return factor < PK_RK45_MIN_FACTOR ? PK_RK45_MIN_FACTOR : factor;
}

/* Decides on an attempted step once all 7 stages are in k and x_new holds the stage-7 position
 * (the fifth-order solution). On acceptance moves x to x_new, time to t + step, and k7 to k1. */
PK_INLINE void pk_rk45_finish_step(pk_rk45_controller* c, double step, double* x, double* k,
                                   const double* x_new) {
  double err;
  int i;
  c->rhs_evaluations += PK_DP_STAGES - 1;
  if (!(pk_is_finite(x_new[0]) && pk_is_finite(x_new[1]) && pk_is_finite(x_new[2]))) {
    c->status = PK_RK45_NON_FINITE;
    return;
  }
  err = pk_rk45_error_norm(step, x, x_new, k, c->relative_tolerance, c->absolute_tolerance);
  if (!pk_is_finite(err)) {
    c->status = PK_RK45_NON_FINITE;
    return;
  }
  if (err <= 1.0) {
    c->accepted_steps += 1;
    for (i = 0; i < 3; ++i) {
      x[i] = x_new[i];
      k[i] = k[18 + i];
    }
    if (c->reaches_end) {
      c->t = c->t_end;
      c->status = PK_RK45_OK;
    } else {
      c->t += step;
      c->h = PK_FABS(step) * pk_rk45_accept_factor(err, c->previous_rejected);
    }
    c->previous_rejected = 0;
  } else {
    c->rejected_steps += 1;
    c->h = PK_FABS(step) * pk_rk45_reject_factor(err);
    c->previous_rejected = 1;
    if (c->h < c->min_step) c->status = PK_RK45_STEP_UNDERFLOW;
  }
  if (c->status == PK_RK45_RUNNING && c->accepted_steps + c->rejected_steps >= c->max_steps) {
    c->status = PK_RK45_MAX_STEPS;
  }
}

/* The whole adaptive loop for one particle, shared by every backend as a macro because OpenCL C has
 * neither templates nor function pointers.
 *   controller: a pk_rk45_controller after pk_rk45_begin
 *   x:          double[3], the particle's position; holds the end (or failure) position afterwards
 *   EVALUATE:   a function or macro called as EVALUATE(point, derivative) with point a double[4]
 *               (x, y, z, t) and derivative a double[3] to receive f(point)
 * Every backend that expands this macro takes the same sequence of decisions, up to rounding. */
#define PK_RK45_INTEGRATE_PARTICLE(controller, x, EVALUATE)                                  \
  do {                                                                                       \
    double pk_k_[3 * PK_DP_STAGES];                                                          \
    double pk_point_[4];                                                                     \
    double pk_x_new_[3];                                                                     \
    int pk_stage_;                                                                           \
    if ((controller).status == PK_RK45_RUNNING) {                                            \
      pk_point_[0] = (x)[0];                                                                 \
      pk_point_[1] = (x)[1];                                                                 \
      pk_point_[2] = (x)[2];                                                                 \
      pk_point_[3] = (controller).t;                                                         \
      EVALUATE(pk_point_, pk_k_);                                                            \
      pk_rk45_record_first_evaluation(&(controller), pk_k_);                                 \
    }                                                                                        \
    while ((controller).status == PK_RK45_RUNNING) {                                         \
      const double pk_step_ = pk_rk45_trial_step(&(controller));                             \
      for (pk_stage_ = 2; pk_stage_ < PK_DP_STAGES; ++pk_stage_) {                           \
        pk_rk45_stage_position(pk_stage_, pk_step_, (x), pk_k_, pk_point_);                  \
        pk_point_[3] = pk_rk45_stage_time(&(controller), pk_stage_, pk_step_);               \
        EVALUATE(pk_point_, &pk_k_[3 * (pk_stage_ - 1)]);                                    \
      }                                                                                      \
      pk_rk45_stage_position(PK_DP_STAGES, pk_step_, (x), pk_k_, pk_x_new_);                 \
      pk_point_[0] = pk_x_new_[0];                                                           \
      pk_point_[1] = pk_x_new_[1];                                                           \
      pk_point_[2] = pk_x_new_[2];                                                           \
      pk_point_[3] = pk_rk45_stage_time(&(controller), PK_DP_STAGES, pk_step_);              \
      EVALUATE(pk_point_, &pk_k_[3 * (PK_DP_STAGES - 1)]);                                   \
      pk_rk45_finish_step(&(controller), pk_step_, (x), pk_k_, pk_x_new_);                   \
    }                                                                                        \
  } while (0)

/* ---------------------------------------------------------------------------------------------- */
/* 5. Every constant, for generators                                                              */
/* ---------------------------------------------------------------------------------------------- */

/* X(NAME) once per double constant above. A generator prints them in another language, e.g. for
 * GLSL:  #define X(name) printf("const double %s = %.17gLF;\n", #name, (double)(name));
 * (17 significant digits round-trip every double exactly). */
#define PK_KERNEL_DOUBLE_CONSTANTS(X)                                                         \
  X(PK_DBL_MIN)                                                                              \
  X(PK_LOG_LN2_HI) X(PK_LOG_LN2_LO) X(PK_LOG_LG1) X(PK_LOG_LG2) X(PK_LOG_LG3) X(PK_LOG_LG4)   \
  X(PK_LOG_LG5) X(PK_LOG_LG6) X(PK_LOG_LG7) X(PK_LOG_EXPONENT_BIAS_MAGIC)                     \
  X(PK_DP_C2) X(PK_DP_C3) X(PK_DP_C4) X(PK_DP_C5) X(PK_DP_C6) X(PK_DP_C7)                     \
  X(PK_DP_A21) X(PK_DP_A31) X(PK_DP_A32) X(PK_DP_A41) X(PK_DP_A42) X(PK_DP_A43)               \
  X(PK_DP_A51) X(PK_DP_A52) X(PK_DP_A53) X(PK_DP_A54)                                         \
  X(PK_DP_A61) X(PK_DP_A62) X(PK_DP_A63) X(PK_DP_A64) X(PK_DP_A65)                            \
  X(PK_DP_B1) X(PK_DP_B3) X(PK_DP_B4) X(PK_DP_B5) X(PK_DP_B6)                                 \
  X(PK_DP_E1) X(PK_DP_E3) X(PK_DP_E4) X(PK_DP_E5) X(PK_DP_E6) X(PK_DP_E7)                     \
  X(PK_RK45_SAFETY) X(PK_RK45_MIN_FACTOR) X(PK_RK45_MAX_FACTOR) X(PK_RK45_ERROR_EXPONENT)     \
  X(PK_RK45_END_STRETCH)

/* X(NAME) once per integer constant above (32-bit words and counts). */
#define PK_KERNEL_WORD_CONSTANTS(X)                                                           \
  X(PK_LOG_ONE_HIGH_WORD) X(PK_LOG_SQRT_HALF_HIGH_WORD) X(PK_LOG_TWO_POW_52_HIGH_WORD)        \
  X(PK_POLYNOMIAL_TERMS) X(PK_DP_STAGES)                                                      \
  X(PK_RK45_RUNNING) X(PK_RK45_OK) X(PK_RK45_MAX_STEPS) X(PK_RK45_STEP_UNDERFLOW)             \
  X(PK_RK45_NON_FINITE)

#endif /* POSEKIT_KERNEL_MATH_H */
