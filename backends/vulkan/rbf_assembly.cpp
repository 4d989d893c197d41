// RBF assembly on Vulkan. The block is cut into rectangles whose points and entries each fit one
// storage-buffer range (lavapipe allows 128 MiB; chunk_bytes() caps it further) and whose centers
// fit the shader's uniform buffer: row blocks of points, within each, runs of columns (centers
// first, then the polynomial terms). Each rectangle is one dispatch of shaders/rbf_assemble.comp;
// the two command slots alternate, so that the device computes one rectangle while the host
// copies the previous one into `block`.
#include "shader_interface.hpp"
#include "vulkan_device.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <array>
#include <string>

namespace posekit::vulkan {
namespace {

// A submitted rectangle still to be copied out.
struct Rectangle {
  bool pending = false;
  Eigen::Index first_row = 0;
  Eigen::Index rows = 0;
  Eigen::Index padded_rows = 0;  // column length in the device buffer: rows rounded up to 4
  Eigen::Index first_column = 0;
  Eigen::Index columns = 0;
};

constexpr VkDeviceSize kPointBytes = 4 * sizeof(double);
constexpr Eigen::Index kQuad = kAssemblyRowsPerInvocation;

Eigen::Index round_up_to_quad(Eigen::Index rows) { return (rows + kQuad - 1) / kQuad * kQuad; }

}  // namespace

void VulkanDevice::do_assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                                         const Eigen::Ref<const Points4>& centers,
                                         bool with_polynomial, Eigen::Ref<Eigen::MatrixXd> block) {
  const Eigen::Index rows = points.rows();
  const Eigen::Index center_count = centers.rows();
  const Eigen::Index columns = center_count + (with_polynomial ? kRbfPolynomialTerms : 0);

  run("assemble_rbf_block", [&] {
    // Whole quads of rows; the constructor guarantees room for at least one.
    const Eigen::Index row_block = batch_size(kPointBytes) / kQuad * kQuad;
    const std::uint64_t max_group_columns =
        std::uint64_t{context_->limits().maxComputeWorkGroupCount[1]} * kAssemblyColumnsPerGroup;
    std::array<Rectangle, 2> rectangles;
    const auto copy_out = [&](std::size_t s) {
      slots_[s]->wait();
      Rectangle& r = rectangles[s];
      block.block(r.first_row, r.first_column, r.rows, r.columns) =
          Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>(
              assembly_blocks_[s].current().as<double>(), r.rows, r.columns,
              Eigen::OuterStride<>(r.padded_rows));
      r.pending = false;
    };
    std::size_t next_slot = 0;
    for (Eigen::Index first_row = 0; first_row < rows; first_row += row_block) {
      const Eigen::Index block_rows = std::min(row_block, rows - first_row);
      const Eigen::Index padded_rows = round_up_to_quad(block_rows);
      // Both slots read the point buffer: let them finish before it is refilled.
      for (std::size_t s = 0; s < rectangles.size(); ++s) {
        if (rectangles[s].pending) copy_out(s);
      }
      const VkDeviceSize point_bytes = static_cast<VkDeviceSize>(padded_rows) * kPointBytes;
      Buffer& point_buffer = assembly_points_.at_least(point_bytes);
      auto* packed_points = point_buffer.as<double>();
      for (Eigen::Index i = 0; i < padded_rows; ++i) {
        // Padding rows repeat the last point; their values are never copied out.
        const Eigen::Index source = first_row + std::min(i, block_rows - 1);
        for (int k = 0; k < 4; ++k) packed_points[4 * i + k] = points(source, k);
      }
      // Columns per rectangle: its entries within one storage-buffer range, its centers within
      // the uniform buffer, its work groups within the dispatch limit.
      const auto column_run = static_cast<Eigen::Index>(std::max<std::uint64_t>(
          1, std::min({chunk_bytes_ / (sizeof(double) * static_cast<std::uint64_t>(padded_rows)),
                       std::uint64_t{kAssemblyCenters}, max_group_columns})));
      for (Eigen::Index first_column = 0; first_column < columns; first_column += column_run) {
        const Eigen::Index run_columns = std::min(column_run, columns - first_column);
        const std::size_t s = next_slot;
        next_slot = 1 - next_slot;
        if (rectangles[s].pending) copy_out(s);

        const Eigen::Index center_columns =
            std::clamp<Eigen::Index>(center_count - first_column, 0, run_columns);
        const Eigen::Index first_term = std::max<Eigen::Index>(first_column - center_count, 0);
        Buffer& center_buffer = assembly_centers_[s].at_least(kAssemblyCenterBytes);
        auto* packed_centers = center_buffer.as<double>();
        for (Eigen::Index j = 0; j < center_columns; ++j) {
          for (int k = 0; k < 4; ++k) packed_centers[4 * j + k] = centers(first_column + j, k);
        }
        const VkDeviceSize entry_bytes = static_cast<VkDeviceSize>(padded_rows) *
                                         static_cast<VkDeviceSize>(run_columns) * sizeof(double);
        Buffer& entries = assembly_blocks_[s].at_least(entry_bytes);

        const auto set = static_cast<std::uint32_t>(s);
        assemble_->write(set, kAssemblyPointsBinding, {{point_buffer.handle(), 0, point_bytes}});
        assemble_->write(set, kAssemblyCentersBinding,
                         {{center_buffer.handle(), 0, kAssemblyCenterBytes}});
        assemble_->write(set, kAssemblyBlockBinding, {{entries.handle(), 0, entry_bytes}});
        const auto row_quads = static_cast<std::uint32_t>(padded_rows / kQuad);
        const AssemblyPush push{row_quads, static_cast<std::uint32_t>(run_columns),
                                static_cast<std::uint32_t>(center_columns),
                                static_cast<std::uint32_t>(first_term)};
        CommandSlot& slot = *slots_[s];
        const VkCommandBuffer commands = slot.begin();
        assemble_->bind(commands, set, &push);
        vkCmdDispatch(commands, (row_quads + kWorkGroupSize - 1) / kWorkGroupSize,
                      static_cast<std::uint32_t>((run_columns + kAssemblyColumnsPerGroup - 1) /
                                                 kAssemblyColumnsPerGroup),
                      1);
        record_shader_to_host_barrier(commands);
        slot.submit();
        rectangles[s] = {true, first_row, block_rows, padded_rows, first_column, run_columns};
      }
    }
    for (std::size_t s = 0; s < rectangles.size(); ++s) {
      if (rectangles[s].pending) copy_out(s);
    }
  });
}

}  // namespace posekit::vulkan
