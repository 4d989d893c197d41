// How many loop iterations one shader invocation may take, and how the operations size their
// dispatches to stay within it. lavapipe (Mesa's llvmpipe) ends every loop of an invocation once
// all its loops together have iterated 65,535 times (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), which
// would silently cut a sum over centers short; other drivers have no such limit. The iteration
// counts below are upper bounds of the loops in shaders/rbf_field.glsl and
// shaders/rk45_integrate.comp; the shaders also count the centers they visit, so that an
// underestimate shows up as an error, never as a wrong value.
#pragma once

#include <cstdint>
#include <limits>

namespace posekit::vulkan {

/// No limit.
inline constexpr std::uint64_t kUnlimitedLoopIterations = std::numeric_limits<std::uint64_t>::max();

/// The budget used on lavapipe: its limit less a margin.
inline constexpr std::uint64_t kLavapipeLoopIterations = 60000;

/// Upper bound of rbf_center_sum's loop iterations over `centers` centers, with the polynomial
/// and the call's own bookkeeping.
std::uint64_t field_value_iterations(std::uint64_t centers);

/// Centers one evaluation dispatch may sum within `budget` (at least 1 when the budget allows
/// any; 0 when it does not).
std::uint64_t centers_per_evaluation(std::uint64_t budget);

/// RK45 steps one round may attempt per particle for a field of `centers` centers within
/// `budget`, at most `max_steps`; 0 when not even one step fits.
std::uint64_t rk45_steps_per_round(std::uint64_t centers, std::uint64_t budget,
                                   std::uint64_t max_steps);

}  // namespace posekit::vulkan
