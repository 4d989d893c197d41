// RBF evaluation on Vulkan: the points in batches that fit one storage buffer, each batch one
// submission of shaders/rbf_evaluate.comp against the uploaded field; a field whose sum over
// centers exceeds one invocation's loop budget (loop_budget.hpp) takes several dispatches over
// ranges of centers, each adding to the previous ones.
#include "loop_budget.hpp"
#include "shader_interface.hpp"
#include "vulkan_device.hpp"

#include <posekit/error.hpp>

#include <string>

namespace posekit::vulkan {

void VulkanDevice::do_evaluate_rbf(const DeviceField& field,
                                   const Eigen::Ref<const Points4>& points,
                                   Eigen::Ref<Eigen::MatrixX3d> values) {
  const VulkanField& vulkan_field = uploaded<VulkanField>(field);
  const Eigen::Index count = points.rows();
  run("evaluate_rbf", [&] {
    const auto centers = static_cast<std::uint64_t>(vulkan_field.center_count());
    const std::uint64_t centers_per_dispatch = centers_per_evaluation(loop_iterations_);
    Buffer& diagnostics = evaluation_diagnostics_.at_least(sizeof(std::uint32_t));
    const Eigen::Index batch = batch_size(4 * sizeof(double));
    for (Eigen::Index first = 0; first < count; first += batch) {
      const Eigen::Index n = std::min(batch, count - first);
      const VkDeviceSize input_bytes = static_cast<VkDeviceSize>(n) * 4 * sizeof(double);
      const VkDeviceSize output_bytes = static_cast<VkDeviceSize>(n) * 3 * sizeof(double);
      Buffer& input = evaluation_points_.at_least(input_bytes);
      Buffer& output = evaluation_values_.at_least(output_bytes);
      auto* packed = input.as<double>();
      for (Eigen::Index i = 0; i < n; ++i) {
        for (int k = 0; k < 4; ++k) packed[4 * i + k] = points(first + i, k);
      }
      *diagnostics.as<std::uint32_t>() = 0;
      evaluate_->write(0, kInputBinding, {{input.handle(), 0, input_bytes}});
      evaluate_->write(0, kOutputBinding, {{output.handle(), 0, output_bytes}});
      evaluate_->write(0, kDiagnosticsBinding, {{diagnostics.handle(), 0, sizeof(std::uint32_t)}});
      vulkan_field.bind_to(*evaluate_, 0);

      CommandSlot& slot = *slots_[0];
      const VkCommandBuffer commands = slot.begin();
      const auto groups = static_cast<std::uint32_t>((n + kWorkGroupSize - 1) / kWorkGroupSize);
      for (std::uint64_t begin = 0;;) {
        const std::uint64_t end =
            centers - begin <= centers_per_dispatch ? centers : begin + centers_per_dispatch;
        const EvaluationPush push{
            static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(begin),
            static_cast<std::uint32_t>(end),
            (begin > 0 ? kAddToValues : 0U) | (end == centers ? kAddPolynomial : 0U)};
        if (begin == 0) {
          evaluate_->bind(commands, 0, &push);
        } else {
          record_shader_to_shader_barrier(commands);
          evaluate_->push(commands, &push);
        }
        vkCmdDispatch(commands, groups, 1, 1);
        if (end == centers) break;
        begin = end;
      }
      record_shader_to_host_barrier(commands);
      slot.submit();
      slot.wait();
      if (*diagnostics.as<const std::uint32_t>() != 0) {
        throw DeviceError("evaluate_rbf: a sum over " + std::to_string(centers) +
                          " centers was cut short by the driver's limit on loop iterations of " +
                          context_->description().driver);
      }
      values.middleRows(first, n) =
          Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
              output.as<double>(), n, 3);
    }
  });
}

}  // namespace posekit::vulkan
