#include "vulkan_field.hpp"

#include "shader_interface.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace posekit::vulkan {

VulkanField::VulkanField(std::shared_ptr<const Context> context, const RbfField& field,
                         std::uint64_t device_id)
    : DeviceField(device_id, static_cast<int>(field.centers.rows())), context_(std::move(context)) {
  const auto centers = static_cast<std::uint64_t>(field.centers.rows());
  const std::uint64_t chunks =
      std::max<std::uint64_t>(1, (centers + kCentersPerChunk - 1) / kCentersPerChunk);
  const std::uint64_t bytes = chunks * kChunkBytes;
  if (bytes > context_->limits().maxStorageBufferRange) {
    throw ArgumentError(
        "upload_field: field.centers has " + std::to_string(centers) +
        " rows, more than one storage buffer of " + context_->description().device_name +
        " holds (" + std::to_string(context_->limits().maxStorageBufferRange / kFieldCenterBytes) +
        " centers)");
  }
  constexpr VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  centers_ = Buffer(context_, bytes, usage, MemoryUse::upload);
  auto* entries = centers_.as<double>();
  std::memset(entries, 0, bytes);
  for (Eigen::Index j = 0; j < field.centers.rows(); ++j) {
    double* entry = entries + 8 * j;
    for (int k = 0; k < 4; ++k) entry[k] = field.centers(j, k);
    for (int k = 0; k < 3; ++k) entry[4 + k] = field.weights(j, k);
  }
  polynomial_ = Buffer(context_, 4 * kRbfPolynomialTerms * sizeof(double),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
  auto* rows = polynomial_.as<double>();
  for (int term = 0; term < kRbfPolynomialTerms; ++term) {
    for (int component = 0; component < 3; ++component) {
      rows[4 * term + component] = field.polynomial(term, component);
    }
    rows[4 * term + 3] = 0.0;
  }
}

void VulkanField::bind_to(ComputePipeline& pipeline, std::uint32_t set) const {
  pipeline.write(set, kCentersBinding, {{centers_.handle(), 0, centers_.size()}});
  pipeline.write(set, kPolynomialBinding, {{polynomial_.handle(), 0, polynomial_.size()}});
  // Every element of the array must be valid; those past the field's last chunk repeat chunk 0
  // (the shader never reads them).
  const VkDeviceSize chunks = centers_.size() / kChunkBytes;
  std::vector<BufferRange> ranges;
  for (std::uint32_t k = 0; k < kUniformChunks; ++k) {
    const VkDeviceSize chunk = k < chunks ? k : 0;
    ranges.push_back({centers_.handle(), chunk * kChunkBytes, kChunkBytes});
  }
  pipeline.write(set, kChunksBinding, ranges);
}

}  // namespace posekit::vulkan
