#include "loop_budget.hpp"

#include "shader_interface.hpp"

#include <algorithm>

namespace posekit::vulkan {
namespace {

// Per sum: up to PK_UNROLL - 1 remainder iterations and one chunk-loop iteration for each uniform
// chunk touched, the same for the storage tail, and a margin.
constexpr std::uint64_t kSumOverhead = (kUniformChunks + 1) * (kCentersPerIteration + 1) + 16;
// Per RK45 step beyond its 6 field values: 6 passes of the stage loop and a margin.
constexpr std::uint64_t kStepOverhead = 16;

}  // namespace

std::uint64_t field_value_iterations(std::uint64_t centers) {
  return (centers + kCentersPerIteration - 1) / kCentersPerIteration + kSumOverhead;
}

std::uint64_t centers_per_evaluation(std::uint64_t budget) {
  if (budget == kUnlimitedLoopIterations) return kUnlimitedLoopIterations;
  if (budget <= kSumOverhead) return 0;
  return (budget - kSumOverhead) * kCentersPerIteration;
}

std::uint64_t rk45_steps_per_round(std::uint64_t centers, std::uint64_t budget,
                                   std::uint64_t max_steps) {
  if (budget == kUnlimitedLoopIterations) return max_steps;
  const std::uint64_t value = field_value_iterations(centers);
  // The first round also takes the first field value (one more pass of the stage loop).
  if (budget < value + 1) return 0;
  const std::uint64_t step = 6 * value + kStepOverhead;
  return std::min(max_steps, (budget - value - 1) / step);
}

}  // namespace posekit::vulkan
