#include "cli_common.hpp"
#include "commands.hpp"

#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include <iostream>
#include <optional>

namespace posekit::cli {
namespace {

struct CheckOptions {
  std::string mesh;
  std::string reference;
  bool json = false;
};

void run_check(const CheckOptions& options) {
  std::vector<std::string> warnings;
  const Mesh mesh = read_mesh(options.mesh, &warnings);
  std::optional<Mesh> reference;
  if (!options.reference.empty()) {
    reference = read_mesh(options.reference, &warnings);
    check_same_connectivity(*reference, options.reference, mesh, options.mesh);
  }
  print_warnings(warnings);

  const std::vector<int> intersecting = self_intersecting_faces(mesh.vertices, mesh.faces);
  nlohmann::json report{{"mesh", options.mesh},
                        {"vertices", mesh.vertices.rows()},
                        {"faces", mesh.faces.rows()},
                        {"self_intersecting_faces", intersecting.size()},
                        {"warnings", warnings}};
  std::cout.setf(std::ios::fixed);
  if (!options.json) {
    std::cout << options.mesh << ": " << mesh.vertices.rows() << " vertices, " << mesh.faces.rows()
              << " faces, " << intersecting.size() << " self-intersecting faces\n";
  }
  if (reference) {
    const std::vector<int> in_reference = self_intersecting_faces(reference->vertices, reference->faces);
    const std::vector<int> fresh = new_intersecting_faces(intersecting, in_reference);
    report["reference"] = options.reference;
    report["reference_self_intersecting_faces"] = in_reference.size();
    report["new_self_intersecting_faces"] = fresh.size();
    if (!options.json) {
      std::cout << fresh.size() << " new against " << options.reference << " (" << in_reference.size()
                << " self-intersecting faces there)\n";
    }
  }
  if (options.json) print_json(report);
}

}  // namespace

void add_check_command(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<CheckOptions>();
  auto* command = app.add_subcommand(
      "check", "Validate a mesh and count its self-intersecting faces (new ones against a reference)");
  command->add_option("MESH", options->mesh, "Mesh file (OBJ, OFF or PLY)")->required();
  command->add_option("--reference", options->reference,
                      "Reference pose with the same connectivity: also count faces that intersect in "
                      "MESH but not in the reference");
  command->add_flag("--json", options->json, "Print a JSON report instead of text");
  command->callback([options, &exit_status] { exit_status = run_guarded([&] { run_check(*options); }); });
}

}  // namespace posekit::cli
