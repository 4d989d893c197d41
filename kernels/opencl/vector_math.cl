/* posekit OpenCL: kernel_math.h's formulas on vectors of PK_VECTOR_WIDTH doubles.
 *
 * The program is kernel_math.h followed by the files of kernels/opencl in the order that
 * backends/opencl/CMakeLists.txt lists; nothing is included at run time. The host defines
 * PK_VECTOR_WIDTH (2, 4 or 8) in the build options.
 *
 * Why vectors by hand: PoCL's CPU device does not turn a scalar sum over centers into vector code
 * (a reduction it may not reorder), while the same loop written on double4 / double8 runs several
 * times faster. Every function here repeats its scalar model from kernel_math.h operation by
 * operation, lane by lane, so each lane rounds exactly as the scalar code does.
 */

#ifndef PK_VECTOR_WIDTH
#define PK_VECTOR_WIDTH 8
#endif

#if PK_VECTOR_WIDTH == 8
typedef double8 pk_vec;
typedef ulong8 pk_uvec;
#define PK_VLOAD vload8
#define PK_VSTORE vstore8
#define PK_AS_VEC as_double8
#define PK_AS_UVEC as_ulong8
#elif PK_VECTOR_WIDTH == 4
typedef double4 pk_vec;
typedef ulong4 pk_uvec;
#define PK_VLOAD vload4
#define PK_VSTORE vstore4
#define PK_AS_VEC as_double4
#define PK_AS_UVEC as_ulong4
#elif PK_VECTOR_WIDTH == 2
typedef double2 pk_vec;
typedef ulong2 pk_uvec;
#define PK_VLOAD vload2
#define PK_VSTORE vstore2
#define PK_AS_VEC as_double2
#define PK_AS_UVEC as_ulong2
#else
#error "PK_VECTOR_WIDTH must be 2, 4 or 8"
#endif

/* pk_log of kernel_math.h, lane by lane (same constants, same operations in the same order). */
PK_INLINE pk_vec pk_log_vec(pk_vec x) {
  pk_uvec bits = PK_AS_UVEC(x);
  bits += (pk_u64)(PK_LOG_ONE_HIGH_WORD - PK_LOG_SQRT_HALF_HIGH_WORD) << 32;
  const pk_vec k =
      PK_AS_VEC((bits >> 52) | ((pk_u64)PK_LOG_TWO_POW_52_HIGH_WORD << 32)) -
      PK_LOG_EXPONENT_BIAS_MAGIC;
  bits = (bits & (((pk_u64)1 << 52) - 1)) + ((pk_u64)PK_LOG_SQRT_HALF_HIGH_WORD << 32);
  const pk_vec f = PK_AS_VEC(bits) - 1.0;
  const pk_vec half_f_squared = 0.5 * f * f;
  const pk_vec s = f / (2.0 + f);
  const pk_vec z = s * s;
  const pk_vec w = z * z;
  const pk_vec even = w * (PK_LOG_LG2 + w * (PK_LOG_LG4 + w * PK_LOG_LG6));
  const pk_vec odd = z * (PK_LOG_LG1 + w * (PK_LOG_LG3 + w * (PK_LOG_LG5 + w * PK_LOG_LG7)));
  const pk_vec r = odd + even;
  return s * (half_f_squared + r) + k * PK_LOG_LN2_LO - half_f_squared + f + k * PK_LOG_LN2_HI;
}

/* pk_squared_distance, lane by lane. */
PK_INLINE pk_vec pk_squared_distance_vec(pk_vec dx, pk_vec dy, pk_vec dz, pk_vec dt) {
  return dx * dx + dy * dy + dz * dz + dt * dt;
}

/* pk_phi_from_squared_distance, lane by lane. */
PK_INLINE pk_vec pk_phi_from_squared_distance_vec(pk_vec r2) {
  return 0.5 * r2 * pk_log_vec(r2 + PK_DBL_MIN);
}

/* Term `term` (0..14) of pk_polynomial_basis at PK_VECTOR_WIDTH points, in the order kernel_math.h
 * documents: 1, x, y, z, t, x^2, x*y, x*z, x*t, y^2, y*z, y*t, z^2, z*t, t^2. */
PK_INLINE pk_vec pk_polynomial_term_vec(int term, pk_vec x, pk_vec y, pk_vec z, pk_vec t) {
  switch (term) {
    case 0: return (pk_vec)(1.0);
    case 1: return x;
    case 2: return y;
    case 3: return z;
    case 4: return t;
    case 5: return x * x;
    case 6: return x * y;
    case 7: return x * z;
    case 8: return x * t;
    case 9: return y * y;
    case 10: return y * z;
    case 11: return y * t;
    case 12: return z * z;
    case 13: return z * t;
    default: return t * t;
  }
}

/* The sum of the lanes, pairwise. */
PK_INLINE double pk_lane_sum(pk_vec v) {
#if PK_VECTOR_WIDTH == 8
  const double4 four = v.lo + v.hi;
  const double2 two = four.lo + four.hi;
  return two.x + two.y;
#elif PK_VECTOR_WIDTH == 4
  const double2 two = v.lo + v.hi;
  return two.x + two.y;
#else
  return v.x + v.y;
#endif
}
