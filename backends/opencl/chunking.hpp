// How work is cut into pieces that fit the device's buffers.
//
// OpenCL caps every buffer at CL_DEVICE_MAX_MEM_ALLOC_SIZE (a quarter of the memory is common; PoCL
// here: 2 GiB). Points, fields and particles are cut into chunks of whole rows, an RBF block into
// tiles of rows by columns. Kernels index with 32-bit ints, so a chunk also stays below
// kMaxChunkItems items.
#pragma once

#include <Eigen/Core>

#include <cstdint>

namespace posekit::opencl {

/// The smallest buffer limit a device may be given (OpenClDeviceOptions::max_buffer_bytes).
constexpr std::uint64_t kMinimumBufferBytes = 4096;

/// The largest number of items in one chunk: keeps every index a kernel computes in an int.
constexpr Eigen::Index kMaxChunkItems = Eigen::Index{1} << 28;

/// `value` rounded up to a multiple of `multiple` (> 0).
Eigen::Index round_up(Eigen::Index value, Eigen::Index multiple);

/// How many items of `bytes_per_item` bytes fit in one buffer of `max_bytes`: rounded down to a
/// multiple of `multiple`, at least `multiple` and at most kMaxChunkItems.
Eigen::Index items_per_buffer(std::uint64_t max_bytes, std::uint64_t bytes_per_item,
                              Eigen::Index multiple);

/// The tiles of an assembled block: `rows` rows (a multiple of the vector width, covering the
/// padded point count or a part of it) by `columns` block columns per tile.
struct TileShape {
  Eigen::Index rows = 0;
  Eigen::Index columns = 0;
};

/// Tiles for a #points by #columns block (centers plus polynomial columns) such that the tile
/// (rows x columns doubles), its points (4 x rows) and its centers (4 x columns) each fit in
/// `max_bytes`. Prefers tiles with every row, so that the points are sent once.
TileShape assembly_tiles(Eigen::Index points, Eigen::Index columns, std::uint64_t max_bytes,
                         Eigen::Index vector_width);

}  // namespace posekit::opencl
