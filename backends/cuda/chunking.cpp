#include "chunking.hpp"

#include <algorithm>

namespace posekit::cuda {

Eigen::Index items_per_chunk(std::uint64_t max_bytes, std::uint64_t bytes_per_item) {
  const std::uint64_t fitting = max_bytes / std::max<std::uint64_t>(bytes_per_item, 1);
  return std::max<Eigen::Index>(
      1, static_cast<Eigen::Index>(std::min<std::uint64_t>(fitting, kMaxChunkItems)));
}

TileShape assembly_tiles(Eigen::Index points, Eigen::Index columns, std::uint64_t max_bytes) {
  constexpr std::uint64_t kDouble = sizeof(double);
  TileShape shape;
  shape.rows = std::min(std::max<Eigen::Index>(points, 1), items_per_chunk(max_bytes, 4 * kDouble));
  const Eigen::Index columns_fitting =
      std::min({items_per_chunk(max_bytes, kDouble * static_cast<std::uint64_t>(shape.rows)),
                items_per_chunk(max_bytes, 4 * kDouble), kMaxTileColumns});
  shape.columns = std::min(std::max<Eigen::Index>(columns, 1), columns_fitting);
  return shape;
}

}  // namespace posekit::cuda
