// The registry: which backends exist, which run here, and how names and POSEKIT_DISABLE_BACKENDS
// are handled.
#include <posekit/cpu_device.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include "device/backend_factory.hpp"

#include "scoped_environment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

namespace posekit {
namespace {

using posekit::testing::ScopedEnvironment;

std::optional<BackendStatus> find_backend(const std::string& name) {
  for (const BackendStatus& status : list_backends()) {
    if (status.name == name) return status;
  }
  return std::nullopt;
}

TEST(Registry, ListsEveryBackendOnceWithCpuLast) {
  const std::vector<BackendStatus> statuses = list_backends();
  ASSERT_FALSE(statuses.empty());
  EXPECT_EQ(statuses.back().name, "cpu");
  for (const char* name : {"cuda", "vulkan", "opencl", "cpu"}) {
    EXPECT_EQ(std::count_if(statuses.begin(), statuses.end(),
                            [&](const BackendStatus& s) { return s.name == name; }),
              1)
        << name;
  }
}

TEST(Registry, CpuIsAvailableWithDoublePrecision) {
  const std::optional<BackendStatus> cpu = find_backend("cpu");
  ASSERT_TRUE(cpu.has_value());
  EXPECT_EQ(cpu->state, BackendState::available) << cpu->reason;
  EXPECT_TRUE(cpu->reason.empty());
  EXPECT_EQ(cpu->info.backend, "cpu");
  EXPECT_TRUE(cpu->info.fp64);
  EXPECT_FALSE(cpu->info.emulated_on_cpu);
  EXPECT_GE(cpu->info.compute_units, 1);
  EXPECT_NE(cpu->info.name.find(" x " + std::to_string(cpu->info.compute_units) + " thread"),
            std::string::npos)
      << cpu->info.name;
}

TEST(Registry, BackendsThatCannotRunSayWhy) {
  for (const BackendStatus& status : list_backends()) {
    if (status.state == BackendState::available) continue;
    EXPECT_FALSE(status.reason.empty()) << status.name << " is " << to_string(status.state);
  }
}

TEST(Registry, CreatesTheCpuDeviceByNameAndAuto) {
  EXPECT_EQ(create_device("cpu")->info().backend, "cpu");
  const std::unique_ptr<Device> automatic = create_device("auto");
  ASSERT_NE(automatic, nullptr);
  const std::optional<BackendStatus> chosen = find_backend(automatic->info().backend);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(chosen->state, BackendState::available);
}

TEST(Registry, UnknownNameThrowsArgumentError) {
  try {
    create_device("quantum");
    FAIL() << "no exception for an unknown backend";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("quantum"), std::string::npos) << error.what();
  }
}

TEST(Registry, DisabledCpuIsUnavailable) {
  const ScopedEnvironment disable("POSEKIT_DISABLE_BACKENDS", "opencl, cpu");
  const std::optional<BackendStatus> cpu = find_backend("cpu");
  ASSERT_TRUE(cpu.has_value());
  EXPECT_EQ(cpu->state, BackendState::unavailable);
  EXPECT_NE(cpu->reason.find("POSEKIT_DISABLE_BACKENDS"), std::string::npos) << cpu->reason;
  try {
    create_device("cpu");
    FAIL() << "created a disabled backend";
  } catch (const ArgumentError& error) {
    FAIL() << "a disabled backend is not a bad argument: " << error.what();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("unavailable"), std::string::npos) << error.what();
  }
}

TEST(Registry, EnabledAgainOnceTheVariableIsGone) {
  { const ScopedEnvironment disable("POSEKIT_DISABLE_BACKENDS", "cpu"); }
  const std::optional<BackendStatus> cpu = find_backend("cpu");
  ASSERT_TRUE(cpu.has_value());
  EXPECT_EQ(cpu->state, BackendState::available);
}

// A backend that probes as an available GPU but fails to create its device, and a working CPU one.
std::vector<detail::BackendFactory> failing_gpu_and_cpu() {
  detail::BackendFactory gpu;
  gpu.name = "gpu";
  gpu.probe = [] {
    BackendStatus status;
    status.state = BackendState::available;
    return status;
  };
  gpu.create = []() -> std::unique_ptr<Device> { throw DeviceError("out of device memory"); };
  detail::BackendFactory cpu;
  cpu.name = "cpu";
  cpu.probe = gpu.probe;
  cpu.create = [] { return make_cpu_device(); };
  return {gpu, cpu};
}

TEST(Registry, AutoFallsBackWhenTheBestDeviceFailsToStart) {
  const std::vector<detail::BackendFactory> factories = failing_gpu_and_cpu();
  const std::unique_ptr<Device> device = detail::create_device(factories, "auto");
  ASSERT_NE(device, nullptr);
  EXPECT_EQ(device->info().backend, "cpu");
  EXPECT_THROW(detail::create_device(factories, "gpu"), DeviceError);
  try {
    detail::create_device({factories.front()}, "auto");
    FAIL() << "created a device from a failing backend";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("gpu: out of device memory"), std::string::npos) << error.what();
  }
}

// A backend for the choice of "auto" that counts what the registry asks of it. Its devices are CPU
// devices, so the counts, not the device, say which backend was chosen.
struct FakeBackend {
  struct Calls {
    int presence_checks = 0;
    int probes = 0;
    int creations = 0;
  };

  std::string name;
  bool gpu_present = true;  // what the presence check answers
  bool available = true;
  bool emulated_on_cpu = false;
  bool fails_to_start = false;
  bool has_presence_check = true;
  std::shared_ptr<Calls> calls = std::make_shared<Calls>();

  detail::BackendFactory factory() const {
    detail::BackendFactory factory;
    factory.name = name;
    factory.probe = [backend = *this] {
      ++backend.calls->probes;
      BackendStatus status;
      status.state = backend.available ? BackendState::available : BackendState::unavailable;
      status.reason = backend.available ? "" : "no driver";
      status.info.emulated_on_cpu = backend.emulated_on_cpu;
      return status;
    };
    factory.create = [backend = *this]() -> std::unique_ptr<Device> {
      ++backend.calls->creations;
      if (backend.fails_to_start) throw DeviceError("out of device memory");
      return make_cpu_device(1);
    };
    if (has_presence_check) {
      factory.may_have_gpu = [backend = *this] {
        ++backend.calls->presence_checks;
        return backend.gpu_present;
      };
    }
    return factory;
  }
};

FakeBackend real_gpu(const std::string& name) { return FakeBackend{name}; }

FakeBackend absent_gpu(const std::string& name) {
  FakeBackend backend{name};
  backend.gpu_present = false;
  backend.available = false;
  return backend;
}

// PoCL or lavapipe: available with no GPU device node at all.
FakeBackend emulation(const std::string& name) {
  FakeBackend backend{name};
  backend.gpu_present = false;
  backend.emulated_on_cpu = true;
  return backend;
}

FakeBackend cpu_backend() {
  FakeBackend backend{"cpu"};
  backend.has_presence_check = false;
  return backend;
}

std::vector<detail::BackendFactory> factories_of(const std::vector<FakeBackend>& backends) {
  std::vector<detail::BackendFactory> factories;
  for (const FakeBackend& backend : backends) factories.push_back(backend.factory());
  return factories;
}

// This machine's case: CUDA built but no NVIDIA driver, Vulkan on lavapipe, OpenCL on PoCL.
TEST(RegistryAuto, WithoutAGpuChoosesCpuWithoutProbingGpuApis) {
  const FakeBackend cuda = absent_gpu("gpu_api");
  const FakeBackend lavapipe = emulation("emulated_api");
  const FakeBackend pocl = emulation("other_emulated_api");
  const FakeBackend cpu = cpu_backend();
  ASSERT_NE(detail::create_device(factories_of({cuda, lavapipe, pocl, cpu}), "auto"), nullptr);
  EXPECT_EQ(cpu.calls->creations, 1);
  for (const FakeBackend& gpu_api : {cuda, lavapipe, pocl}) {
    EXPECT_EQ(gpu_api.calls->presence_checks, 1) << gpu_api.name;
    EXPECT_EQ(gpu_api.calls->probes, 0) << gpu_api.name << " was started without a GPU to find";
    EXPECT_EQ(gpu_api.calls->creations, 0) << gpu_api.name;
  }
}

TEST(RegistryAuto, PrefersARealGpuToCpuAndEmulations) {
  FakeBackend driver_missing = absent_gpu("gpu_api");
  driver_missing.gpu_present = true;  // a device node, but this API finds no GPU behind it
  FakeBackend pocl_beside_a_gpu = emulation("emulated_api");
  pocl_beside_a_gpu.gpu_present = true;
  const FakeBackend gpu = real_gpu("other_gpu_api");
  const FakeBackend cpu = cpu_backend();
  ASSERT_NE(detail::create_device(factories_of({driver_missing, pocl_beside_a_gpu, gpu, cpu}), "auto"),
            nullptr);
  EXPECT_EQ(gpu.calls->creations, 1);
  EXPECT_EQ(driver_missing.calls->probes, 1);
  EXPECT_EQ(driver_missing.calls->creations, 0);
  EXPECT_EQ(pocl_beside_a_gpu.calls->probes, 1);
  EXPECT_EQ(pocl_beside_a_gpu.calls->creations, 0) << "an emulation was preferred to a real GPU";
  EXPECT_EQ(cpu.calls->creations, 0) << "the CPU backend was preferred to a real GPU";
  EXPECT_EQ(cpu.calls->probes, 0) << "probed on after the first real GPU started";
}

TEST(RegistryAuto, UsesAnEmulationOnlyWhenTheCpuBackendIsUnavailable) {
  const FakeBackend pocl = emulation("emulated_api");
  {
    const FakeBackend cpu = cpu_backend();
    detail::create_device(factories_of({pocl, cpu}), "auto");
    EXPECT_EQ(cpu.calls->creations, 1);
    EXPECT_EQ(pocl.calls->creations, 0);
  }
  {
    FakeBackend cpu = cpu_backend();
    cpu.fails_to_start = true;
    detail::create_device(factories_of({pocl, cpu}), "auto");
    EXPECT_EQ(cpu.calls->creations, 1);
    EXPECT_EQ(pocl.calls->creations, 1) << "no fallback to the emulation after the cpu backend failed";
  }
  {
    const ScopedEnvironment disable("POSEKIT_DISABLE_BACKENDS", "cpu");
    const FakeBackend cpu = cpu_backend();
    detail::create_device(factories_of({pocl, cpu}), "auto");
    EXPECT_EQ(cpu.calls->probes, 0);
    EXPECT_EQ(cpu.calls->creations, 0);
    EXPECT_EQ(pocl.calls->creations, 2) << "no fallback to the emulation with the cpu backend disabled";
  }
}

TEST(RegistryAuto, SkipsDisabledBackends) {
  const ScopedEnvironment disable("POSEKIT_DISABLE_BACKENDS", "gpu_api");
  const FakeBackend gpu = real_gpu("gpu_api");
  const FakeBackend cpu = cpu_backend();
  detail::create_device(factories_of({gpu, cpu}), "auto");
  EXPECT_EQ(gpu.calls->probes, 0);
  EXPECT_EQ(gpu.calls->creations, 0) << "created a disabled backend";
  EXPECT_EQ(cpu.calls->creations, 1);
  try {
    detail::create_device(factories_of({gpu}), "auto");
    FAIL() << "created a device with every backend disabled";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("no compute device is available"), std::string::npos)
        << error.what();
  }
}

TEST(RegistryAuto, FallsThroughBackendsThatFailToStart) {
  FakeBackend failing_gpu = real_gpu("gpu_api");
  failing_gpu.fails_to_start = true;
  const FakeBackend second_gpu = real_gpu("other_gpu_api");
  const FakeBackend cpu = cpu_backend();
  detail::create_device(factories_of({failing_gpu, second_gpu, cpu}), "auto");
  EXPECT_EQ(failing_gpu.calls->creations, 1);
  EXPECT_EQ(second_gpu.calls->creations, 1);
  EXPECT_EQ(cpu.calls->creations, 0);
}

TEST(RegistryAuto, TriesEachBackendOnceAndNamesEveryFailure) {
  FakeBackend failing_gpu = real_gpu("gpu_api");
  failing_gpu.fails_to_start = true;
  FakeBackend failing_cpu = cpu_backend();
  failing_cpu.fails_to_start = true;
  try {
    detail::create_device(factories_of({failing_gpu, failing_cpu}), "auto");
    FAIL() << "created a device from failing backends";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what())
                  .find("could be created (gpu_api: out of device memory; cpu: out of device memory)"),
              std::string::npos)
        << error.what();
  }
  EXPECT_EQ(failing_gpu.calls->creations, 1);
  EXPECT_EQ(failing_cpu.calls->creations, 1);
}

TEST(RegistryAuto, ProbesAGpuApiWithoutPresenceCheckAsBefore) {
  FakeBackend unchecked = real_gpu("gpu_api");
  unchecked.has_presence_check = false;
  const FakeBackend cpu = cpu_backend();
  detail::create_device(factories_of({unchecked, cpu}), "auto");
  EXPECT_EQ(unchecked.calls->creations, 1);
  EXPECT_EQ(cpu.calls->creations, 0);
}

TEST(RegistryAuto, EveryGpuApiOfThisBuildHasAPresenceCheck) {
  for (const detail::BackendFactory& factory : detail::builtin_backends()) {
    if (factory.name == "cpu") continue;
    EXPECT_TRUE(factory.may_have_gpu) << factory.name << " would be started on every machine";
  }
}

TEST(Registry, StatesHaveNames) {
  EXPECT_STREQ(to_string(BackendState::available), "available");
  EXPECT_STREQ(to_string(BackendState::unavailable), "unavailable");
  EXPECT_STREQ(to_string(BackendState::not_built), "not built");
}

}  // namespace
}  // namespace posekit
