// The SPIR-V of posekit's compute shaders, compiled from <root>/shaders at build time and embedded
// here, so that no file is looked up at run time.
#pragma once

#include <cstdint>
#include <vector>

namespace posekit::vulkan {

enum class Shader { rbf_assemble, rbf_evaluate, rk45_integrate };

/// The shader's SPIR-V words.
const std::vector<std::uint32_t>& spirv(Shader shader);

}  // namespace posekit::vulkan
