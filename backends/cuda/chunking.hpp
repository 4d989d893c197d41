// How the CUDA backend cuts work into pieces that fit its scratch budget and the kernels' index
// range. Points and particles go over in chunks of whole rows, an RBF block in tiles of rows by
// columns. Kernels index within a chunk with 32-bit ints and the grid's y extent is limited to
// 65,535 blocks, so a chunk holds at most kMaxChunkItems items and a tile at most kMaxTileColumns
// columns.
#pragma once

#include <Eigen/Core>

#include <cstdint>

namespace posekit::cuda {

/// The smallest scratch budget a device may be given (CudaDeviceOptions::max_chunk_bytes).
constexpr std::uint64_t kMinimumChunkBytes = 4096;

/// The budget used when none is given: large enough that a launch runs for milliseconds, small
/// beside any data-centre GPU's memory.
constexpr std::uint64_t kDefaultChunkBytes = std::uint64_t{256} << 20;

/// The most items (points, particles, rows) in one chunk: keeps every index in an int and every
/// column of a chunk below 2 GiB, the largest pitch of a rectangular copy.
constexpr Eigen::Index kMaxChunkItems = Eigen::Index{1} << 27;

/// The most columns of one assembly tile (65,535 blocks of 32 columns in the grid's y).
constexpr Eigen::Index kMaxTileColumns = Eigen::Index{65535} * 32;

/// How many items of `bytes_per_item` bytes fit in `max_bytes`: at least 1, at most
/// kMaxChunkItems.
Eigen::Index items_per_chunk(std::uint64_t max_bytes, std::uint64_t bytes_per_item);

/// The tiles of an assembled block.
struct TileShape {
  Eigen::Index rows = 0;
  Eigen::Index columns = 0;
};

/// Tiles for a #points by #columns block (centers plus polynomial columns) such that the tile
/// (rows x columns doubles), its points (4 x rows) and its centers (4 x columns) each fit in
/// `max_bytes`. Prefers tiles with every row, so that the points are sent once.
TileShape assembly_tiles(Eigen::Index points, Eigen::Index columns, std::uint64_t max_bytes);

}  // namespace posekit::cuda
