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

/* pk_log, pk_squared_distance and pk_phi_from_squared_distance of kernel_math.h, lane by lane:
 * the same definitions for the vector type. */
PK_DEFINE_LOG(pk_log_vec, pk_vec, pk_uvec, PK_AS_UVEC, PK_AS_VEC)
PK_DEFINE_SQUARED_DISTANCE(pk_squared_distance_vec, pk_vec)
PK_DEFINE_PHI_FROM_SQUARED_DISTANCE(pk_phi_from_squared_distance_vec, pk_vec, pk_log_vec)

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
