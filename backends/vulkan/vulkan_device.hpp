// The Vulkan device: a Context, the three compute pipelines built once at creation, two command
// slots (so that assembly can compute one rectangle while the host copies out the previous one)
// and scratch buffers reused from call to call. Operations are serialized (Device's front holds
// the lock): a Vulkan queue and command pool take one thread at a time. One file per operation: rbf_assembly.cpp,
// rbf_evaluation.cpp, rk45.cpp.
#pragma once

#include "vulkan_buffer.hpp"
#include "vulkan_context.hpp"
#include "vulkan_field.hpp"
#include "vulkan_pipeline.hpp"

#include <posekit/device.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>

namespace posekit::vulkan {

/// What the registry reports for a discovered device.
DeviceInfo describe(const DiscoveredDevice& device);

/// Limits a VulkanDevice imposes on itself below the device's own; tests set them low to exercise
/// the splitting of work that the device's limits otherwise only force at large sizes.
struct DeviceTuning {
  /// Largest storage-buffer range one dispatch writes or reads; 0: the device's
  /// maxStorageBufferRange, at most 64 MiB. At least 64.
  std::uint64_t max_chunk_bytes = 0;
  /// Loop iterations one shader invocation may take (loop_budget.hpp); 0: the driver's
  /// (kLavapipeLoopIterations on lavapipe, unlimited elsewhere).
  std::uint64_t loop_iterations = 0;
};

class VulkanDevice final : public Device {
 public:
  /// Creates the context (with the validation layer when `validation`) and the pipelines. Throws
  /// DeviceError, or ArgumentError for a tuning out of range.
  explicit VulkanDevice(bool validation, DeviceTuning tuning = {});
  ~VulkanDevice() override;

  DeviceInfo info() const override;

  /// The Vulkan objects underneath (for tests that run their own shaders).
  const std::shared_ptr<const Context>& context() const { return context_; }
  /// Bytes of the largest storage-buffer range one dispatch uses.
  std::uint64_t chunk_bytes() const { return chunk_bytes_; }
  /// Loop iterations one shader invocation may take (kUnlimitedLoopIterations: no limit).
  std::uint64_t loop_iterations() const { return loop_iterations_; }

 protected:
  void do_assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                             const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                             Eigen::Ref<Eigen::MatrixXd> block) override;
  std::unique_ptr<DeviceField> do_upload_field(const RbfField& field) override;
  void do_evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                       Eigen::Ref<Eigen::MatrixX3d> values) override;
  std::vector<Rk45ParticleStats> do_integrate_rk45(const DeviceField& field,
                                                   Eigen::Ref<Eigen::MatrixX3d> positions,
                                                   const Rk45Options& options) override;

 private:
  // Runs `body`; afterwards (also when it throws) no submission is pending, and
  // with validation on, any message of the layer meanwhile becomes a DeviceError naming
  // `operation`.
  void run(const char* operation, const std::function<void()>& body);
  // Points per dispatch when each takes `bytes_per_point` of one storage buffer.
  Eigen::Index batch_size(std::uint64_t bytes_per_point) const;

  std::shared_ptr<const Context> context_;
  std::uint64_t chunk_bytes_;
  std::uint64_t loop_iterations_;
  std::unique_ptr<ComputePipeline> assemble_;
  std::unique_ptr<ComputePipeline> evaluate_;
  std::unique_ptr<ComputePipeline> rk45_;
  std::array<std::unique_ptr<CommandSlot>, 2> slots_;
  ScratchBuffer assembly_points_;
  std::array<ScratchBuffer, 2> assembly_centers_;
  std::array<ScratchBuffer, 2> assembly_blocks_;
  ScratchBuffer evaluation_points_;
  ScratchBuffer evaluation_values_;
  ScratchBuffer evaluation_diagnostics_;
  ScratchBuffer rk45_states_;
};

}  // namespace posekit::vulkan
