// How the CUDA backend cuts work into chunks and tiles (backends/cuda/chunking.hpp): pure
// arithmetic, checked on any machine.
#include "cuda/chunking.hpp"
#include "cuda/cuda_kernels.hpp"

#include <gtest/gtest.h>

namespace posekit::cuda {
namespace {

TEST(CudaChunking, ItemsPerChunkStaysWithinTheBudgetAndTheIndexRange) {
  EXPECT_EQ(items_per_chunk(chunk_limits(4096), 32), 128);
  EXPECT_EQ(items_per_chunk(chunk_limits(4095), 32), 127);
  EXPECT_EQ(items_per_chunk(chunk_limits(16), 32), 1) << "at least one item, whatever the budget";
  EXPECT_EQ(items_per_chunk(chunk_limits(std::uint64_t{1} << 40), 8), kMaxChunkItems);
  EXPECT_LE(kMaxChunkItems * 8, std::int64_t{1} << 31) << "a column of a chunk is one copy pitch";
}

TEST(CudaChunking, AssemblyTilesFitTheBudget) {
  struct Case {
    Eigen::Index points;
    Eigen::Index columns;
    std::uint64_t budget;
  };
  for (const Case c : {Case{65000, 2715, kDefaultChunkBytes}, Case{1031, 272, kMinimumChunkBytes},
                       Case{1, 5, kMinimumChunkBytes}, Case{7, 1, kMinimumChunkBytes},
                       Case{300000000, 143, kDefaultChunkBytes}}) {
    SCOPED_TRACE(std::to_string(c.points) + " x " + std::to_string(c.columns));
    const TileShape tile = assembly_tiles(chunk_limits(c.budget), c.points, c.columns);
    EXPECT_GE(tile.rows, 1);
    EXPECT_GE(tile.columns, 1);
    EXPECT_LE(tile.rows, c.points);
    EXPECT_LE(tile.columns, c.columns);
    EXPECT_LE(static_cast<std::uint64_t>(tile.rows * tile.columns) * sizeof(double), c.budget);
    EXPECT_LE(static_cast<std::uint64_t>(4 * tile.rows) * sizeof(double), c.budget);
    EXPECT_LE(static_cast<std::uint64_t>(4 * tile.columns) * sizeof(double), c.budget);
    EXPECT_LE(tile.rows, kMaxChunkItems);
  }
  // A pose's constraints against one round's centers: one tile of every row and column.
  const TileShape round = assembly_tiles(chunk_limits(kDefaultChunkBytes), 65000, 143);
  EXPECT_EQ(round.rows, 65000);
  EXPECT_EQ(round.columns, 143);
}

TEST(CudaChunking, AssemblyTilesStayWithinTheGrid) {
  // One point against millions of centers: the columns of a tile are bounded by the grid's y.
  const TileShape tile = assembly_tiles(chunk_limits(std::uint64_t{1} << 30), 1, 10000000);
  EXPECT_EQ(tile.columns, kMaxTileColumns);
  EXPECT_LE((tile.columns + kAssemblyColumns - 1) / kAssemblyColumns, kMaxGridY);
}

}  // namespace
}  // namespace posekit::cuda
