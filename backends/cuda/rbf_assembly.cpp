// RBF assembly on a CUDA device: the block is computed in tiles of rows by columns that fit the
// scratch budget (kernels/cuda/rbf_assembly.cu), each copied straight into its place in the
// caller's block with one rectangular copy.
#include "chunking.hpp"
#include "cuda_check.hpp"
#include "cuda_kernels.hpp"
#include "cuda_operations.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <string>

namespace posekit::cuda {

void assemble_rbf_block(CudaContext& context, const Eigen::Ref<const Points4>& points,
                        const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                        Eigen::Ref<Eigen::MatrixXd> block) {
  const Eigen::Index rows = points.rows();
  const Eigen::Index center_count = centers.rows();
  const Eigen::Index columns = center_count + (with_polynomial ? kRbfPolynomialTerms : 0);
  if (center_count > kMaxChunkItems) {
    throw ArgumentError("assemble_rbf_block: centers has " + std::to_string(center_count) +
                        " rows, more than the CUDA kernels index (" +
                        std::to_string(kMaxChunkItems) + ")");
  }
  const TileShape tile = assembly_tiles(chunk_limits(context.max_chunk_bytes), rows, columns);
  double* const point_buffer =
      context.scratch_buffer(Scratch::points, 4 * sizeof(double) * tile.rows).as<double>();
  double* const center_buffer =
      context.scratch_buffer(Scratch::centers, 4 * sizeof(double) * tile.columns).as<double>();
  double* const tile_buffer =
      context.scratch_buffer(Scratch::tile, sizeof(double) * tile.rows * tile.columns).as<double>();
  for (Eigen::Index first_row = 0; first_row < rows; first_row += tile.rows) {
    const Eigen::Index tile_rows = std::min(tile.rows, rows - first_row);
    copy_columns(context, point_buffer, tile.rows, points.data() + first_row, points.outerStride(),
                 tile_rows, 4, cudaMemcpyHostToDevice);
    for (Eigen::Index first_column = 0; first_column < columns; first_column += tile.columns) {
      const Eigen::Index tile_columns = std::min(tile.columns, columns - first_column);
      const Eigen::Index tile_centers =
          std::clamp<Eigen::Index>(center_count - first_column, 0, tile_columns);
      copy_columns(context, center_buffer, tile.columns, centers.data() + first_column,
                   centers.outerStride(), tile_centers, 4, cudaMemcpyHostToDevice);
      AssemblyTile launch;
      launch.points = PointsView{point_buffer, static_cast<int>(tile_rows),
                                 static_cast<int>(tile.rows)};
      launch.centers = center_buffer;
      launch.center_stride = static_cast<int>(tile.columns);
      launch.center_count = static_cast<int>(center_count);
      launch.first_column = static_cast<int>(first_column);
      launch.columns = static_cast<int>(tile_columns);
      launch.tile = tile_buffer;
      launch.tile_stride = static_cast<int>(tile.rows);
      POSEKIT_CUDA_CHECK(launch_rbf_assemble(launch, context.stream));
      copy_columns(context, block.data() + first_column * block.outerStride() + first_row,
                   block.outerStride(), tile_buffer, tile.rows, tile_rows, tile_columns,
                   cudaMemcpyDeviceToHost);
    }
  }
  context.synchronize();
}

}  // namespace posekit::cuda
