// How a GPU backend cuts work into pieces that fit its buffers and its kernels' index range.
// Points, fields and particles go over in chunks of whole rows, an RBF block in tiles of rows by
// columns.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <limits>

namespace posekit::backends {

/// What one chunk may hold on a device.
struct ChunkLimits {
  std::uint64_t max_bytes = 0;  ///< bytes of one buffer (or scratch allocation)
  Eigen::Index max_items = 0;   ///< items (points, particles, rows) a kernel indexes in one chunk
  /// Columns of one assembly tile that a launch can cover (a grid dimension's limit).
  Eigen::Index max_tile_columns = std::numeric_limits<Eigen::Index>::max();
};

/// `value` rounded up to a multiple of `multiple` (> 0).
Eigen::Index round_up(Eigen::Index value, Eigen::Index multiple);

/// How many items of `bytes_per_item` bytes fit in one chunk: rounded down to a multiple of
/// `multiple` (a vector width; 1 for none), at least `multiple` and at most limits.max_items.
Eigen::Index items_per_chunk(const ChunkLimits& limits, std::uint64_t bytes_per_item,
                             Eigen::Index multiple = 1);

/// The tiles of an assembled block.
struct TileShape {
  Eigen::Index rows = 0;     ///< a multiple of the row multiple
  Eigen::Index columns = 0;  ///< block columns (centers, then polynomial terms)
};

/// Tiles for a #points by #columns block such that the tile (rows x columns doubles), its points
/// (4 x rows) and its centers (4 x columns) each fit one chunk. Prefers tiles with every row, so
/// that the points are sent once; rows are a multiple of `row_multiple`.
TileShape assembly_tiles(const ChunkLimits& limits, Eigen::Index points, Eigen::Index columns,
                         Eigen::Index row_multiple = 1);

}  // namespace posekit::backends
