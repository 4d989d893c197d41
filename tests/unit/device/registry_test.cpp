// The registry: which backends exist, which run here, and how names and POSEKIT_DISABLE_BACKENDS
// are handled.
#include <posekit/cpu_device.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>

#include "device/backend_factory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>

namespace posekit {
namespace {

// Sets an environment variable for the lifetime of the object and restores the previous state.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* previous = std::getenv(name)) previous_ = previous;
    setenv(name, value, 1);
  }
  ~ScopedEnvironment() {
    if (previous_) {
      setenv(name_.c_str(), previous_->c_str(), 1);
    } else {
      unsetenv(name_.c_str());
    }
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  std::string name_;
  std::optional<std::string> previous_;
};

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

TEST(Registry, StatesHaveNames) {
  EXPECT_STREQ(to_string(BackendState::available), "available");
  EXPECT_STREQ(to_string(BackendState::unavailable), "unavailable");
  EXPECT_STREQ(to_string(BackendState::not_built), "not built");
}

}  // namespace
}  // namespace posekit
