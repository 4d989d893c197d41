// The CUDA device: one stream on the GPU that discovery chose, kernels checked for it once when the
// device is created; the operations live in rbf_assembly.cpp, rbf_evaluation.cpp and rk45.cpp.
#include "cuda_device.hpp"

#include "chunking.hpp"
#include "cuda_check.hpp"
#include "cuda_context.hpp"
#include "cuda_discovery.hpp"
#include "cuda_field.hpp"
#include "cuda_kernels.hpp"
#include "cuda_operations.hpp"

#include <posekit/error.hpp>

#include <algorithm>
#include <string>

namespace posekit::cuda {
namespace {

class CudaDevice final : public Device {
 public:
  CudaDevice(const DiscoveredDevice& found, const CudaDeviceOptions& options)
      : Device(Calls::serialized), info_(describe(found)) {
    context_.ordinal = found.ordinal;
    context_.id = id();
    context_.make_current();
    // Every kernel must have code for this GPU; the runtime loads modules lazily, so ask now
    // rather than at the first launch.
    cudaFuncAttributes attributes{};
    POSEKIT_CUDA_CHECK(rbf_assemble_attributes(&attributes));
    POSEKIT_CUDA_CHECK(rbf_evaluate_attributes(&attributes));
    POSEKIT_CUDA_CHECK(rk45_attributes(&attributes));
    int blocks_per_multiprocessor = 0;
    POSEKIT_CUDA_CHECK(rk45_blocks_per_multiprocessor(&blocks_per_multiprocessor));
    context_.rk45_max_blocks = options.rk45_blocks > 0
                                   ? options.rk45_blocks
                                   : std::max(1, blocks_per_multiprocessor) *
                                         std::max(1, found.multiprocessors);
    context_.max_chunk_bytes =
        options.max_chunk_bytes != 0
            ? options.max_chunk_bytes
            : std::max(kMinimumChunkBytes,
                       std::min<std::uint64_t>(kDefaultChunkBytes, found.global_memory_bytes / 8));
    POSEKIT_CUDA_CHECK(cudaStreamCreateWithFlags(&context_.stream, cudaStreamNonBlocking));
  }

  ~CudaDevice() override {
    // Scratch buffers go first (their destructors free them), then the stream. Errors are ignored:
    // at process exit the runtime may be gone already.
    for (DeviceBuffer& buffer : context_.scratch) buffer = DeviceBuffer();
    if (context_.stream != nullptr) cudaStreamDestroy(context_.stream);
    cudaGetLastError();
  }

  DeviceInfo info() const override { return info_; }

  // Serialized: the operations share one stream and scratch buffers; each makes the device
  // current on the calling thread first.
 protected:
  void do_assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                             const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                             Eigen::Ref<Eigen::MatrixXd> block) override {
    context_.make_current();
    cuda::assemble_rbf_block(context_, points, centers, with_polynomial, block);
  }

  std::unique_ptr<DeviceField> do_upload_field(const RbfField& field) override {
    context_.make_current();
    return std::make_unique<CudaField>(context_, field);
  }

  void do_evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                       Eigen::Ref<Eigen::MatrixX3d> values) override {
    context_.make_current();
    cuda::evaluate_rbf(context_, uploaded<CudaField>(field), points, values);
  }

  std::vector<Rk45ParticleStats> do_integrate_rk45(const DeviceField& field,
                                                   Eigen::Ref<Eigen::MatrixX3d> positions,
                                                   const Rk45Options& options) override {
    context_.make_current();
    return cuda::integrate_rk45(context_, uploaded<CudaField>(field), positions, options);
  }

 private:
  DeviceInfo info_;
  CudaContext context_;
};

}  // namespace

std::unique_ptr<Device> make_cuda_device(const CudaDeviceOptions& options) {
  if (options.max_chunk_bytes != 0 && options.max_chunk_bytes < kMinimumChunkBytes) {
    throw ArgumentError("make_cuda_device: max_chunk_bytes must be 0 (the default) or at least " +
                        std::to_string(kMinimumChunkBytes) + ", got " +
                        std::to_string(options.max_chunk_bytes));
  }
  if (options.rk45_blocks < 0) {
    throw ArgumentError("make_cuda_device: rk45_blocks must be 0 (as many as the GPU holds) or "
                        "positive, got " + std::to_string(options.rk45_blocks));
  }
  const Discovery discovery = discover_device();
  if (!discovery.device) throw DeviceError("no CUDA device: " + discovery.reason);
  return std::make_unique<CudaDevice>(*discovery.device, options);
}

}  // namespace posekit::cuda
