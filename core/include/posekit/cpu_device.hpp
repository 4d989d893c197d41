// The CPU backend, created directly rather than through the registry.
#pragma once

#include <posekit/device.hpp>

#include <memory>

namespace posekit {

/// Creates a CPU device: multithreaded with TBB, its hot loops vectorized for the widest
/// instruction set this processor has (the library itself stays portable). threads: number of
/// worker threads, 0 (default) for all hardware threads; more than the hardware has are capped.
/// Throws ArgumentError when threads < 0.
std::unique_ptr<Device> make_cpu_device(int threads = 0);

}  // namespace posekit
