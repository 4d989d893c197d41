/* posekit OpenCL: the value of an uploaded field at one point, shared by the evaluation and the
 * RK45 kernels.
 *
 * Layout of a field's center data (one buffer, structure of arrays): seven columns of `stride`
 * doubles each, center x, y, z, t then weight x, y, z; stride is a multiple of PK_VECTOR_WIDTH and
 * at least the center count. The polynomial is a separate buffer of 45 doubles, the column-major
 * 15 by 3 posekit::RbfPolynomial.
 */

/* sum[0..2] = sum_j w_j phi(|point - c_j|) over `count` centers; point is (x, y, z, t) in private
 * memory. Whole vectors of centers first, each lane summing every PK_VECTOR_WIDTH-th center and
 * the lanes added pairwise at the end, then the last count % PK_VECTOR_WIDTH centers one by one:
 * the zeros that pad the columns never enter the sum. */
PK_INLINE void pk_rbf_sum(__global const double* field, int count, int stride, const double* point,
                          double* sum) {
  __global const double* cx = field;
  __global const double* cy = field + stride;
  __global const double* cz = field + 2 * (size_t)stride;
  __global const double* ct = field + 3 * (size_t)stride;
  __global const double* wx = field + 4 * (size_t)stride;
  __global const double* wy = field + 5 * (size_t)stride;
  __global const double* wz = field + 6 * (size_t)stride;
  const double px = point[0];
  const double py = point[1];
  const double pz = point[2];
  const double pt = point[3];
  const int vector_end = count - count % PK_VECTOR_WIDTH;
  pk_vec sx = (pk_vec)(0.0);
  pk_vec sy = (pk_vec)(0.0);
  pk_vec sz = (pk_vec)(0.0);
  int j;
  for (j = 0; j < vector_end; j += PK_VECTOR_WIDTH) {
    const pk_vec phi = pk_phi_from_squared_distance_vec(
        pk_squared_distance_vec(px - PK_VLOAD(0, cx + j), py - PK_VLOAD(0, cy + j),
                                pz - PK_VLOAD(0, cz + j), pt - PK_VLOAD(0, ct + j)));
    sx += phi * PK_VLOAD(0, wx + j);
    sy += phi * PK_VLOAD(0, wy + j);
    sz += phi * PK_VLOAD(0, wz + j);
  }
  double x = pk_lane_sum(sx);
  double y = pk_lane_sum(sy);
  double z = pk_lane_sum(sz);
  for (; j < count; ++j) {
    const double phi = pk_phi_from_squared_distance(
        pk_squared_distance(px - cx[j], py - cy[j], pz - cz[j], pt - ct[j]));
    x += phi * wx[j];
    y += phi * wy[j];
    z += phi * wz[j];
  }
  sum[0] = x;
  sum[1] = y;
  sum[2] = z;
}

/* Copies the 45 polynomial coefficients into private memory, where pk_polynomial_value reads them. */
PK_INLINE void pk_load_polynomial(__global const double* polynomial, double* coefficients) {
  int k;
  for (k = 0; k < 3 * PK_POLYNOMIAL_TERMS; ++k) coefficients[k] = polynomial[k];
}

/* value[0..2] = f(point): the sum over centers plus the polynomial, as the CPU backend adds them. */
PK_INLINE void pk_field_value(__global const double* field, int count, int stride,
                              const double* coefficients, const double* point, double* value) {
  int c;
  pk_rbf_sum(field, count, stride, point, value);
  for (c = 0; c < 3; ++c) {
    value[c] += pk_polynomial_value(coefficients + c * PK_POLYNOMIAL_TERMS, point[0], point[1],
                                    point[2], point[3]);
  }
}
