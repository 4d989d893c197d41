#include "chunking.hpp"

#include <algorithm>

namespace posekit::opencl {

Eigen::Index round_up(Eigen::Index value, Eigen::Index multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

Eigen::Index items_per_buffer(std::uint64_t max_bytes, std::uint64_t bytes_per_item,
                              Eigen::Index multiple) {
  const std::uint64_t fitting = max_bytes / bytes_per_item;
  const Eigen::Index capped =
      static_cast<Eigen::Index>(std::min<std::uint64_t>(fitting, kMaxChunkItems));
  return std::max(multiple, capped / multiple * multiple);
}

TileShape assembly_tiles(Eigen::Index points, Eigen::Index columns, std::uint64_t max_bytes,
                         Eigen::Index vector_width) {
  constexpr std::uint64_t kDouble = sizeof(double);
  TileShape shape;
  shape.rows = std::min(round_up(std::max<Eigen::Index>(points, 1), vector_width),
                        items_per_buffer(max_bytes, 4 * kDouble, vector_width));
  const Eigen::Index columns_fitting = std::min(
      items_per_buffer(max_bytes, kDouble * static_cast<std::uint64_t>(shape.rows), 1),
      items_per_buffer(max_bytes, 4 * kDouble, 1));
  shape.columns = std::min(std::max<Eigen::Index>(columns, 1), columns_fitting);
  return shape;
}

}  // namespace posekit::opencl
