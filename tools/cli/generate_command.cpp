#include "cli_common.hpp"
#include "commands.hpp"
#include "demo_poses.hpp"

#include <iostream>

namespace posekit::cli {

void add_generate_command(CLI::App& app, int& exit_status) {
  struct GenerateOptions {
    std::string output_dir = "posekit-demo";
    std::string format = "obj";
    DemoArmOptions arm;
  };
  auto options = std::make_shared<GenerateOptions>();
  auto* command = app.add_subcommand(
      "generate", "Write posekit's own articulated test shape: a capsule arm at rest and bent by skinning");
  command->add_option("--output-dir", options->output_dir, "Folder for the pose files")->capture_default_str();
  command->add_option("--format", options->format, "File format of the poses")
      ->check(CLI::IsMember({"obj", "off", "ply"}))
      ->capture_default_str();
  command->add_option("--angles", options->arm.bend_angles_degrees, "Bend angles in degrees, one pose each")
      ->capture_default_str();
  command->add_option("--ring-segments", options->arm.ring_segments,
                      "Vertices around each ring of the tube (>= 8, a multiple of 4)")
      ->capture_default_str();
  command->add_option("--length", options->arm.cylinder_length,
                      "Length of the tube between its caps, the joint at its middle (at least the joint's blend "
                      "width, 1): longer arms, same joint")
      ->check(CLI::Range(1.0, 1.0e6))
      ->capture_default_str();
  command->callback([options, &exit_status] {
    exit_status = run_guarded([&] {
      for (const auto& file : write_demo_poses(options->arm, options->output_dir, options->format)) {
        std::cout << "wrote " << file.string() << "\n";
      }
    });
  });
}

}  // namespace posekit::cli
