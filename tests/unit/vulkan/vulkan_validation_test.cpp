// The validation layer is really on in tests and stays silent: a deliberate misuse is caught and
// turned into a DeviceError, synchronization validation reports a missing barrier, a whole device
// life (every operation, a field outliving its device) produces no message, and the registry
// switches the layer on through POSEKIT_VULKAN_VALIDATION.
#include "vulkan_test_support.hpp"
#include "scoped_environment.hpp"

#include "vulkan/vulkan_buffer.hpp"
#include "vulkan/vulkan_validation.hpp"

#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include <Eigen/Core>

#include <cstdlib>
#include <optional>
#include <random>

namespace posekit::vulkan {
namespace {

using posekit::testing::ScopedEnvironment;

Points4 random_points(std::mt19937_64& engine, Eigen::Index count) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  Points4 points(count, 4);
  for (Eigen::Index i = 0; i < points.size(); ++i) points.data()[i] = coordinate(engine);
  return points;
}

TEST(VulkanValidation, CatchesADeliberateMisuse) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  ASSERT_TRUE(device->context()->validation());
  const std::size_t first = validation_message_count();
  // A buffer of size 0 with no usage breaks two valid-usage rules of VkBufferCreateInfo.
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = 0;
  info.usage = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer(device->context()->device(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS && buffer != VK_NULL_HANDLE) {
    vkDestroyBuffer(device->context()->device(), buffer, nullptr);
  }
  const std::vector<std::string> messages = validation_messages_since(first);
  ASSERT_FALSE(messages.empty()) << "the validation layer did not report vkCreateBuffer(size 0)";
  bool names_the_rule = false;
  for (const std::string& message : messages) {
    names_the_rule |= message.find("VUID-VkBufferCreateInfo-size-00912") != std::string::npos;
  }
  EXPECT_TRUE(names_the_rule) << messages.front();
  EXPECT_THROW(throw_if_validation_messages(first, "the misuse"), DeviceError);
}

TEST(VulkanValidation, SynchronizationValidationIsOn) {
  POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
  const std::shared_ptr<const Context>& context = device->context();
  Buffer buffer(context, 1024,
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                MemoryUse::readback);
  CommandSlot slot(context);
  const auto fill_twice = [&](bool barrier) {
    const VkCommandBuffer commands = slot.begin();
    vkCmdFillBuffer(commands, buffer.handle(), 0, buffer.size(), 1);
    if (barrier) {
      VkMemoryBarrier between{};
      between.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
      between.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      between.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                           0, 1, &between, 0, nullptr, 0, nullptr);
    }
    vkCmdFillBuffer(commands, buffer.handle(), 0, buffer.size(), 2);
    slot.submit();
    slot.wait();
  };
  std::size_t first = validation_message_count();
  fill_twice(true);
  EXPECT_EQ(validation_message_count(), first) << "two writes separated by a barrier are fine";
  first = validation_message_count();
  fill_twice(false);
  const std::vector<std::string> messages = validation_messages_since(first);
  ASSERT_FALSE(messages.empty()) << "two writes of one buffer without a barrier went unreported";
  EXPECT_NE(messages.front().find("SYNC-HAZARD-WRITE-AFTER-WRITE"), std::string::npos)
      << messages.front();
}

TEST(VulkanValidation, AWholeDeviceLifeIsSilent) {
  const std::size_t first = validation_message_count();
  std::unique_ptr<DeviceField> survivor;
  {
    POSEKIT_VALIDATED_VULKAN_DEVICE_OR_SKIP(device);
    std::mt19937_64 engine(3);
    const Points4 points = random_points(engine, 70);
    RbfField field;
    field.centers = random_points(engine, 9);
    field.weights = Eigen::MatrixX3d::Constant(9, 3, 0.01);
    Eigen::MatrixXd block(70, 9 + kRbfPolynomialTerms);
    device->assemble_rbf_block(points, field.centers, true, block);
    const std::unique_ptr<DeviceField> uploaded = device->upload_field(field);
    Eigen::MatrixX3d values(70, 3);
    device->evaluate_rbf(*uploaded, points, values);
    Eigen::MatrixX3d positions = points.leftCols<3>();
    device->integrate_rk45(*uploaded, positions, Rk45Options());
    // Kept past the device's end: its buffers hold the Vulkan objects they need.
    survivor = device->upload_field(field);
  }
  survivor.reset();
  const std::vector<std::string> messages = validation_messages_since(first);
  EXPECT_TRUE(messages.empty()) << messages.size()
                                << " message(s); the first: " << messages.front();
}

TEST(VulkanValidation, RegistryDevicesFollowTheEnvironment) {
  std::string reason;
  if (!testing::make_validated_device(reason)) GTEST_SKIP() << reason;
  {
    const ScopedEnvironment on("POSEKIT_VULKAN_VALIDATION", "1");
    const std::unique_ptr<Device> device = create_device("vulkan");
    const auto* vulkan_device = dynamic_cast<const VulkanDevice*>(device.get());
    ASSERT_NE(vulkan_device, nullptr);
    EXPECT_TRUE(vulkan_device->context()->validation());
  }
  {
    const ScopedEnvironment off("POSEKIT_VULKAN_VALIDATION", "0");
    const std::unique_ptr<Device> device = create_device("vulkan");
    EXPECT_FALSE(dynamic_cast<const VulkanDevice&>(*device).context()->validation());
  }
}

}  // namespace
}  // namespace posekit::vulkan
