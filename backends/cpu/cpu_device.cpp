// The CPU device: a TBB arena of worker threads and the instruction set of its hot loops.
#include "cpu_device.hpp"

#include "cpu_field.hpp"
#include "cpu_operations.hpp"

#include <posekit/cpu_device.hpp>
#include <posekit/error.hpp>

#include <tbb/info.h>
#include <tbb/task_arena.h>
#include <tbb/version.h>

#include <algorithm>
#include <exception>
#include <fstream>
#include <string>

namespace posekit {
namespace cpu {
namespace {

int hardware_threads() { return std::max(1, tbb::info::default_concurrency()); }

// "model name" from /proc/cpuinfo where there is one.
std::string processor_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) break;
    const std::size_t begin = line.find_first_not_of(" \t", colon + 1);
    if (begin == std::string::npos) break;
    return line.substr(begin);
  }
  return "CPU";
}

DeviceInfo describe(int threads, KernelIsa isa) {
  DeviceInfo info;
  info.backend = "cpu";
  info.name =
      processor_model() + " x " + std::to_string(threads) + (threads == 1 ? " thread" : " threads");
  info.driver = std::string("oneTBB ") + TBB_VERSION_STRING + ", " + to_string(isa) + " kernels";
  info.fp64 = true;
  info.emulated_on_cpu = false;
  info.max_buffer_bytes = 0;
  info.compute_units = threads;
  return info;
}

class CpuDevice final : public Device {
 public:
  // Concurrent: the arena takes work from any number of callers' threads.
  CpuDevice(int threads, KernelIsa isa)
      : Device(Calls::concurrent), threads_(threads), isa_(isa), arena_(threads) {}

  DeviceInfo info() const override { return describe(threads_, isa_); }

 protected:
  void do_assemble_rbf_block(const Eigen::Ref<const Points4>& points,
                             const Eigen::Ref<const Points4>& centers, bool with_polynomial,
                             Eigen::Ref<Eigen::MatrixXd> block) override {
    cpu::assemble_rbf_block(execution(), points, centers, with_polynomial, block);
  }

  std::unique_ptr<DeviceField> do_upload_field(const RbfField& field) override {
    return std::make_unique<CpuField>(field, id());
  }

  void do_evaluate_rbf(const DeviceField& field, const Eigen::Ref<const Points4>& points,
                       Eigen::Ref<Eigen::MatrixX3d> values) override {
    cpu::evaluate_rbf(execution(), uploaded<CpuField>(field), points, values);
  }

  std::vector<Rk45ParticleStats> do_integrate_rk45(const DeviceField& field,
                                                   Eigen::Ref<Eigen::MatrixX3d> positions,
                                                   const Rk45Options& options) override {
    return cpu::integrate_rk45(execution(), uploaded<CpuField>(field), positions, options);
  }

 private:
  CpuExecution execution() { return {arena_, isa_}; }

  int threads_;
  KernelIsa isa_;
  tbb::task_arena arena_;
};

BackendStatus probe() {
  BackendStatus status;
  status.name = "cpu";
  try {
    status.info = describe(hardware_threads(), best_supported_isa());
    status.state = BackendState::available;
  } catch (const std::exception& error) {
    status.state = BackendState::unavailable;
    status.reason = error.what();
  }
  return status;
}

}  // namespace

detail::BackendFactory backend_factory() {
  // No presence check: "auto" knows the cpu backend by its name and tries it after real GPUs.
  return detail::BackendFactory{"cpu", probe, [] { return posekit::make_cpu_device(0); }, nullptr};
}

std::unique_ptr<Device> make_cpu_device(int threads, KernelIsa isa) {
  if (threads < 0) {
    throw ArgumentError("make_cpu_device: threads must be >= 0 (0 for all hardware threads), got " +
                        std::to_string(threads));
  }
  if (!is_supported(isa)) {
    throw ArgumentError(std::string("make_cpu_device: isa ") + to_string(isa) +
                        " is not supported by this processor or build");
  }
  // More threads than the hardware has would only oversubscribe it (and make TBB complain).
  const int available = hardware_threads();
  return std::make_unique<CpuDevice>(threads == 0 ? available : std::min(threads, available), isa);
}

}  // namespace cpu

std::unique_ptr<Device> make_cpu_device(int threads) {
  return cpu::make_cpu_device(threads, cpu::best_supported_isa());
}

}  // namespace posekit
