#include "cli_common.hpp"
#include "commands.hpp"
#include "demo_poses.hpp"

#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include <chrono>
#include <iomanip>
#include <iostream>

namespace posekit::cli {
namespace {

void run_demo(const std::string& output_dir) {
  const auto start = std::chrono::steady_clock::now();
  const DemoArmOptions arm;
  const std::vector<std::filesystem::path> files = write_demo_poses(arm, output_dir, "obj");
  const Mesh rest = read_mesh(files.front());
  std::cout << "generated " << files.size() << " poses of the demo arm (" << rest.vertices.rows()
            << " vertices, " << rest.faces.rows() << " faces) in " << output_dir << "\n";

  const std::vector<int> rest_intersections = self_intersecting_faces(rest.vertices, rest.faces);
  std::cout << std::left << std::setw(24) << "pose" << std::right << std::setw(14) << "intersecting"
            << std::setw(8) << "new" << "\n";
  std::cout << std::left << std::setw(24) << files.front().filename().string() << std::right << std::setw(14)
            << rest_intersections.size() << std::setw(8) << "-" << "\n";
  for (size_t pose = 1; pose < files.size(); ++pose) {
    const Mesh bent = read_mesh(files[pose]);
    const std::vector<int> intersecting = self_intersecting_faces(bent.vertices, bent.faces);
    const std::vector<int> fresh = new_intersecting_faces(intersecting, rest_intersections);
    std::cout << std::left << std::setw(24) << files[pose].filename().string() << std::right << std::setw(14)
              << intersecting.size() << std::setw(8) << fresh.size() << "\n";
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "checked in " << std::fixed << std::setprecision(2) << seconds << " s\n";
}

}  // namespace

void add_demo_command(CLI::App& app, int& exit_status) {
  auto output_dir = std::make_shared<std::string>("posekit-demo");
  auto* command = app.add_subcommand(
      "demo", "Generate the demo arm's poses and count the self-intersections that bending creates");
  command->add_option("--output-dir", *output_dir, "Folder for the generated poses")->capture_default_str();
  command->callback([output_dir, &exit_status] { exit_status = run_guarded([&] { run_demo(*output_dir); }); });
}

}  // namespace posekit::cli
