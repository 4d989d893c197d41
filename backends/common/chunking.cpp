#include "chunking.hpp"

#include <algorithm>

namespace posekit::backends {

Eigen::Index round_up(Eigen::Index value, Eigen::Index multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

Eigen::Index items_per_chunk(const ChunkLimits& limits, std::uint64_t bytes_per_item,
                             Eigen::Index multiple) {
  const std::uint64_t fitting = limits.max_bytes / std::max<std::uint64_t>(bytes_per_item, 1);
  const auto max_items = static_cast<std::uint64_t>(limits.max_items);
  const auto capped = static_cast<Eigen::Index>(std::min(fitting, max_items));
  return std::max(multiple, capped / multiple * multiple);
}

TileShape assembly_tiles(const ChunkLimits& limits, Eigen::Index points, Eigen::Index columns,
                         Eigen::Index row_multiple) {
  constexpr std::uint64_t kDouble = sizeof(double);
  TileShape shape;
  shape.rows = std::min(round_up(std::max<Eigen::Index>(points, 1), row_multiple),
                        items_per_chunk(limits, 4 * kDouble, row_multiple));
  const Eigen::Index columns_fitting =
      std::min({items_per_chunk(limits, kDouble * static_cast<std::uint64_t>(shape.rows)),
                items_per_chunk(limits, 4 * kDouble), limits.max_tile_columns});
  shape.columns = std::min(std::max<Eigen::Index>(columns, 1), columns_fitting);
  return shape;
}

}  // namespace posekit::backends
