/* posekit OpenCL: one tile of an RBF block, A(i, j) = phi(|y_i - c_j|) for center columns and the
 * polynomial terms pi_k(y_i) for the 15 columns after them.
 *
 * The tile covers columns first_column .. first_column + tile_columns - 1 of the whole block
 * (#centers + 15 polynomial columns when the host asks for them) and every row of its points.
 * Points: four columns (x, y, z, t) of point_stride doubles; rows beyond the real ones are padding
 * whose results the host does not read. Centers: four columns of center_stride doubles holding the
 * centers of this tile, the first one being center first_column. The tile is column-major with
 * leading dimension point_stride. One work-item writes PK_VECTOR_WIDTH consecutive rows of
 * PK_ASSEMBLY_COLUMNS consecutive columns: its points are loaded once for all of them, and PoCL's
 * CPU device spends less on scheduling per evaluation than with one column per work-item.
 */
#ifndef PK_ASSEMBLY_COLUMNS
#define PK_ASSEMBLY_COLUMNS 8
#endif

__kernel void pk_rbf_assemble(__global const double* points, int point_stride,
                              __global const double* centers, int center_stride,
                              int center_count, int first_column, int tile_columns,
                              __global double* tile) {
  const int row = (int)get_global_id(0) * PK_VECTOR_WIDTH;
  const int first = (int)get_global_id(1) * PK_ASSEMBLY_COLUMNS;
  if (row >= point_stride) return;
  const pk_vec x = PK_VLOAD(0, points + row);
  const pk_vec y = PK_VLOAD(0, points + point_stride + row);
  const pk_vec z = PK_VLOAD(0, points + 2 * (size_t)point_stride + row);
  const pk_vec t = PK_VLOAD(0, points + 3 * (size_t)point_stride + row);
  const int end = min(first + PK_ASSEMBLY_COLUMNS, tile_columns);
  int column;
  for (column = first; column < end; ++column) {
    const int block_column = first_column + column;
    pk_vec value;
    if (block_column < center_count) {
      const double cx = centers[column];
      const double cy = centers[center_stride + column];
      const double cz = centers[2 * (size_t)center_stride + column];
      const double ct = centers[3 * (size_t)center_stride + column];
      value = pk_phi_from_squared_distance_vec(
          pk_squared_distance_vec(x - cx, y - cy, z - cz, t - ct));
    } else {
      value = pk_polynomial_term_vec(block_column - center_count, x, y, z, t);
    }
    PK_VSTORE(value, 0, tile + (size_t)column * point_stride + row);
  }
}
