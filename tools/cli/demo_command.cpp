#include "cli_common.hpp"
#include "commands.hpp"
#include "demo_poses.hpp"

#include <posekit/correct.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/mesh_io.hpp>

#include <iomanip>
#include <iostream>

namespace posekit::cli {
namespace {

void run_demo(const std::string& output_dir, const std::string& device_name) {
  const DemoArmOptions arm;
  const std::vector<std::filesystem::path> files = write_demo_poses(arm, output_dir, "obj");
  const Mesh rest = read_mesh(files.front());
  std::cout << "generated " << files.size() << " poses of the demo arm (" << rest.vertices.rows() << " vertices, "
            << rest.faces.rows() << " faces) in " << output_dir << "\n";
  std::unique_ptr<Device> device = create_device(device_name);
  std::cout << "correcting each bent pose against the rest pose on " << device->info().backend << " ("
            << device->info().name << ")\n";
  std::cout << std::left << std::setw(22) << "pose" << std::right << std::setw(16) << "intersecting" << std::setw(16)
            << "after correct" << std::setw(8) << "new" << std::setw(10) << "centers" << std::setw(10) << "seconds"
            << "\n";
  for (size_t pose = 1; pose < files.size(); ++pose) {
    const Mesh bent = read_mesh(files[pose]);
    CorrectionReport report;
    const Eigen::MatrixX3d corrected = correct_pose(rest.vertices, bent.vertices, rest.faces, *device, {}, &report);
    std::filesystem::path output = files[pose];
    output.replace_filename(files[pose].stem().string() + "-corrected.obj");
    write_mesh(output, Mesh{corrected, rest.faces});
    std::cout << std::left << std::setw(22) << files[pose].filename().string() << std::right << std::setw(16)
              << report.result.target_intersecting_faces << std::setw(16) << report.result.intersecting_faces
              << std::setw(8) << report.result.new_intersecting_faces << std::setw(10) << report.field.centers()
              << std::setw(10) << std::fixed << std::setprecision(2) << report.seconds << "\n";
  }
  std::cout << "corrected poses written beside the generated ones (*-corrected.obj)\n";
}

}  // namespace

void add_demo_command(CLI::App& app, int& exit_status) {
  auto output_dir = std::make_shared<std::string>("posekit-demo");
  auto device = std::make_shared<std::string>("auto");
  auto* command = app.add_subcommand(
      "demo", "Generate the demo arm, bent until it self-intersects, and correct each bent pose");
  command->add_option("--output-dir", *output_dir, "Folder for the generated and corrected poses")
      ->capture_default_str();
  command->add_option("--device", *device, "Compute device")->capture_default_str();
  command->callback([output_dir, device, &exit_status] {
    exit_status = run_guarded([&] { run_demo(*output_dir, *device); });
  });
}

}  // namespace posekit::cli
