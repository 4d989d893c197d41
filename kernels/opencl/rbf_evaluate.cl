/* posekit OpenCL: field values at a batch of points, one work-item per point.
 *
 * Points: four columns (x, y, z, t) of point_stride doubles; values: three columns of point_stride
 * doubles. A field too large for one buffer comes in several parts (rbf_field.cl's layout each):
 * the first launch writes sum + polynomial (accumulate = 0), the launches for the other parts add
 * their sums (accumulate = 1, with_polynomial = 0).
 */
__kernel void pk_rbf_evaluate(__global const double* field, int center_count, int center_stride,
                              __global const double* polynomial, int with_polynomial,
                              __global const double* points, int point_count, int point_stride,
                              int accumulate, __global double* values) {
  const int i = (int)get_global_id(0);
  if (i >= point_count) return;
  double point[4];
  double sum[3];
  int c;
  point[0] = points[i];
  point[1] = points[point_stride + i];
  point[2] = points[2 * (size_t)point_stride + i];
  point[3] = points[3 * (size_t)point_stride + i];
  pk_rbf_sum(field, center_count, center_stride, point, sum);
  if (with_polynomial) {
    double coefficients[3 * PK_POLYNOMIAL_TERMS];
    pk_load_polynomial(polynomial, coefficients);
    for (c = 0; c < 3; ++c) {
      sum[c] += pk_polynomial_value(coefficients + c * PK_POLYNOMIAL_TERMS, point[0], point[1],
                                    point[2], point[3]);
    }
  }
  for (c = 0; c < 3; ++c) {
    __global double* value = values + c * (size_t)point_stride + i;
    *value = accumulate ? *value + sum[c] : sum[c];
  }
}
