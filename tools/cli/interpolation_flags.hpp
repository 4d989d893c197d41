// The interpolation's command-line flags, shared by `interpolate` and the Python package: one
// definition of each flag, its default and its check; and the JSON of one interpolated pose.
#pragma once

#include <posekit/interpolate.hpp>
#include <posekit/interpolation_error.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace posekit::cli {

struct InterpolationFlags {
  std::string method = "mixit";
  InterpolationOptions interpolation;
};

/// Registers --method and the tuning options of the three methods on `command`, stored in `flags`.
void add_interpolation_flags(CLI::App* command, InterpolationFlags& flags);

/// The options the flags ask for (the method set from its name).
InterpolationOptions interpolation_options(const InterpolationFlags& flags);

/// One output: its `weights`, `gauss_newton_iterations`, `error` against the linearly interpolated
/// edge lengths and dihedral angles, and the `seconds` of its steps.
nlohmann::json interpolation_step_json(const Eigen::VectorXd& weights, const InterpolationStepReport& step,
                                       const InterpolationError& error);

}  // namespace posekit::cli
