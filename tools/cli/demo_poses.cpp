#include "demo_poses.hpp"

#include <posekit/mesh_io.hpp>

#include <cmath>
#include <cstdio>

namespace posekit::cli {

std::string demo_pose_file_name(double bend_angle_degrees, const std::string& extension) {
  const double magnitude = std::abs(bend_angle_degrees);
  char number[32];
  if (magnitude == std::round(magnitude)) {
    std::snprintf(number, sizeof number, "%03.0f", magnitude);
  } else {
    std::snprintf(number, sizeof number, "%05.1f", magnitude);
  }
  return std::string("arm-bent-") + (bend_angle_degrees < 0 ? "m" : "") + number + "." + extension;
}

std::vector<std::filesystem::path> write_demo_poses(const DemoArmOptions& options,
                                                    const std::filesystem::path& folder,
                                                    const std::string& extension) {
  const PoseSet poses = make_demo_arm(options);
  std::filesystem::create_directories(folder);
  std::vector<std::filesystem::path> files{folder / ("arm-rest." + extension)};
  for (double angle : options.bend_angles_degrees) files.push_back(folder / demo_pose_file_name(angle, extension));
  for (int pose = 0; pose < poses.pose_count(); ++pose) {
    write_mesh(files[static_cast<size_t>(pose)], poses.mesh(pose));
  }
  return files;
}

}  // namespace posekit::cli
