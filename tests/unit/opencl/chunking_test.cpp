// Chunk and tile planning: every piece fits the buffer limit, vectors stay whole, and nothing is
// cut that fits.
#include "opencl/chunking.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace posekit::opencl {
namespace {

TEST(Chunking, ItemsPerBufferRoundDownToTheMultiple) {
  EXPECT_EQ(items_per_chunk(chunk_limits(4096), 56, 8), 72);  // 73 fit, 72 is the last multiple of 8
  EXPECT_EQ(items_per_chunk(chunk_limits(4096), 56, 1), 73);
  EXPECT_EQ(items_per_chunk(chunk_limits(4096), 32, 1), 128);
}

TEST(Chunking, ItemsPerBufferKeepsOneVectorAndStaysIndexable) {
  EXPECT_EQ(items_per_chunk(chunk_limits(100), 56, 8), 8) << "at least one whole vector";
  EXPECT_EQ(items_per_chunk(chunk_limits(std::uint64_t{1} << 62), 8, 8), kMaxChunkItems);
}

TEST(Chunking, RoundUp) {
  EXPECT_EQ(round_up(0, 8), 0);
  EXPECT_EQ(round_up(1, 8), 8);
  EXPECT_EQ(round_up(16, 8), 16);
  EXPECT_EQ(round_up(1031, 4), 1032);
}

TEST(Chunking, AssemblyTilesFitTheLimit) {
  for (const std::uint64_t limit : {std::uint64_t{4096}, std::uint64_t{65536},
                                    std::uint64_t{1} << 20, std::uint64_t{256} << 20}) {
    for (const Eigen::Index width : {2, 4, 8}) {
      for (const Eigen::Index points : {1, 7, 1031, 65000, 1000003}) {
        for (const Eigen::Index columns : {1, 16, 272, 2715}) {
          const TileShape tile = assembly_tiles(chunk_limits(limit), points, columns, width);
          SCOPED_TRACE(::testing::Message() << "limit " << limit << " width " << width << " points "
                                            << points << " columns " << columns);
          EXPECT_EQ(tile.rows % width, 0);
          EXPECT_GE(tile.rows, width);
          EXPECT_LE(tile.rows, round_up(points, width));
          EXPECT_GE(tile.columns, 1);
          EXPECT_LE(tile.columns, columns);
          EXPECT_LE(static_cast<std::uint64_t>(tile.rows * tile.columns) * 8, limit);
          EXPECT_LE(static_cast<std::uint64_t>(4 * tile.rows) * 8, limit);
          EXPECT_LE(static_cast<std::uint64_t>(4 * tile.columns) * 8, limit);
        }
      }
    }
  }
}

TEST(Chunking, AssemblyTilesCoverASmallBlockAtOnce) {
  const TileShape tile = assembly_tiles(chunk_limits(std::uint64_t{256} << 20), 128, 2715, 8);
  EXPECT_EQ(tile.rows, 128);
  EXPECT_EQ(tile.columns, 2715);
}

TEST(Chunking, AssemblyTilesKeepEveryRowOfALargeBlock) {
  // 65,000 x 2,715 doubles (1.4 GB) in 256 MiB tiles: all rows, a sixth of the columns each.
  const TileShape tile = assembly_tiles(chunk_limits(std::uint64_t{256} << 20), 65000, 2715, 8);
  EXPECT_EQ(tile.rows, 65000);
  EXPECT_EQ(tile.columns, (std::int64_t{256} << 20) / 8 / 65000);
}

}  // namespace
}  // namespace posekit::opencl
