// RBF assembly on an OpenCL device: the block is computed in tiles of rows by columns that fit the
// device's buffers (kernels/opencl/rbf_assembly.cl), each read straight into its place in the
// caller's block.
#include "chunking.hpp"
#include "kernel_launch.hpp"
#include "opencl_operations.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <limits>
#include <string>

namespace posekit::opencl {

void assemble_rbf_block(OpenClRuntime& runtime, const Eigen::Ref<const Points4>& points,
                        const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                        Eigen::Ref<Eigen::MatrixXd> block) {
  const Eigen::Index rows = points.rows();
  const Eigen::Index center_count = centers.rows();
  const Eigen::Index columns = center_count + (with_polynomial ? kRbfPolynomialTerms : 0);
  const Eigen::Index width = runtime.vector_width;
  const TileShape tile = assembly_tiles(chunk_limits(runtime.max_tile_bytes), rows, columns, width);
  const cl::Buffer point_buffer =
      scratch_buffer(runtime, Scratch::points, 4 * sizeof(double) * tile.rows);
  const cl::Buffer center_buffer =
      scratch_buffer(runtime, Scratch::centers, 4 * sizeof(double) * tile.columns);
  const cl::Buffer tile_buffer =
      scratch_buffer(runtime, Scratch::tile, sizeof(double) * tile.rows * tile.columns);
  for (Eigen::Index first_row = 0; first_row < rows; first_row += tile.rows) {
    const Eigen::Index tile_rows = std::min(tile.rows, rows - first_row);
    write_buffer(runtime, point_buffer, pack_columns(points, first_row, tile_rows, tile.rows));
    for (Eigen::Index first_column = 0; first_column < columns; first_column += tile.columns) {
      const Eigen::Index tile_columns = std::min(tile.columns, columns - first_column);
      const Eigen::Index tile_centers =
          std::clamp<Eigen::Index>(center_count - first_column, 0, tile_columns);
      if (tile_centers > 0) {
        write_buffer(runtime, center_buffer,
                     pack_columns(centers, first_column, tile_centers, tile.columns));
      }
      set_arguments(runtime.assemble, "pk_rbf_assemble", point_buffer, static_cast<int>(tile.rows),
                    center_buffer, static_cast<int>(tile.columns), static_cast<int>(center_count),
                    static_cast<int>(first_column), static_cast<int>(tile_columns), tile_buffer);
      // Work-items over vectors of rows (only as many as this tile has) by groups of columns.
      const std::size_t row_items = static_cast<std::size_t>(round_up(tile_rows, width) / width);
      const std::size_t column_items =
          static_cast<std::size_t>(round_up(tile_columns, kAssemblyColumns) / kAssemblyColumns);
      // One group size for every tile: PoCL compiles a kernel anew for each group size it meets
      // (0.1 s), more than the idle work-items of a short tile cost.
      const std::size_t group = runtime.assemble_group;
      const std::size_t global_rows = (row_items + group - 1) / group * group;
      const cl_int status = runtime.queue.enqueueNDRangeKernel(
          runtime.assemble, cl::NullRange, cl::NDRange(global_rows, column_items),
          cl::NDRange(group, 1));
      POSEKIT_CL_CHECK(status, "clEnqueueNDRangeKernel(pk_rbf_assemble)");
      read_columns(runtime, tile_buffer, tile.rows, tile_rows, tile_columns, block.data(),
                   block.outerStride(), first_row, first_column);
    }
  }
}

}  // namespace posekit::opencl
