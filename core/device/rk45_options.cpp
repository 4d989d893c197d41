#include <posekit/device.hpp>
#include <posekit/error.hpp>

#include <cmath>
#include <sstream>

namespace posekit {
namespace {

[[noreturn]] void reject_option(const char* option, const char* requirement, double value) {
  std::ostringstream message;
  message << "integrate_rk45: options." << option << " must be " << requirement << " (got " << value
          << ")";
  throw ArgumentError(message.str());
}

}  // namespace

void validate_rk45_options(const Rk45Options& options) {
  if (!std::isfinite(options.t_begin)) reject_option("t_begin", "finite", options.t_begin);
  if (!std::isfinite(options.t_end)) reject_option("t_end", "finite", options.t_end);
  validate_rk45_step_control(options);
}

void validate_rk45_step_control(const Rk45StepControl& options) {
  if (!(std::isfinite(options.relative_tolerance) && options.relative_tolerance >= 0.0)) {
    reject_option("relative_tolerance", "finite and >= 0", options.relative_tolerance);
  }
  // A zero absolute tolerance would divide by zero on a component that is exactly 0.
  if (!(std::isfinite(options.absolute_tolerance) && options.absolute_tolerance > 0.0)) {
    reject_option("absolute_tolerance", "finite and > 0", options.absolute_tolerance);
  }
  if (!(std::isfinite(options.initial_step) && options.initial_step > 0.0)) {
    reject_option("initial_step", "finite and > 0", options.initial_step);
  }
  if (!(std::isfinite(options.min_step) && options.min_step >= 0.0)) {
    reject_option("min_step", "finite and >= 0", options.min_step);
  }
  if (options.max_steps <= 0) reject_option("max_steps", "> 0", options.max_steps);
}

}  // namespace posekit
