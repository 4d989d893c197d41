// Writing the demo arm's poses to files, shared by `posekit generate` and `posekit demo`.
#pragma once

#include <posekit/demo_shape.hpp>

#include <filesystem>
#include <vector>

namespace posekit::cli {

/// File name of a demo pose: "arm-rest.obj" or "arm-bent-090.obj" ("arm-bent-m045.obj" for -45).
std::string demo_pose_file_name(double bend_angle_degrees, const std::string& extension);

/// Generates the arm and writes every pose into `folder` (created if missing); returns the files,
/// rest pose first.
std::vector<std::filesystem::path> write_demo_poses(const DemoArmOptions& options,
                                                    const std::filesystem::path& folder,
                                                    const std::string& extension);

}  // namespace posekit::cli
