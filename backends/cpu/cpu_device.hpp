// The CPU backend as the registry and the tests see it.
#pragma once

#include "device/backend_factory.hpp"
#include "kernel_isa.hpp"

#include <posekit/device.hpp>

#include <memory>

namespace posekit::cpu {

/// The registry entry "cpu": always available, created with every hardware thread.
detail::BackendFactory backend_factory();

/// A CPU device with `threads` worker threads (0, or more than the hardware has: all hardware
/// threads) whose hot loops use the copy compiled for `isa`. Throws ArgumentError for threads < 0
/// or an isa this processor lacks.
std::unique_ptr<Device> make_cpu_device(int threads, KernelIsa isa);

}  // namespace posekit::cpu
