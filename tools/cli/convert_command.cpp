#include "cli_common.hpp"
#include "commands.hpp"

#include <posekit/mesh_io.hpp>

#include <iostream>

namespace posekit::cli {

void add_convert_command(CLI::App& app, int& exit_status) {
  struct ConvertOptions {
    std::string input;
    std::string output;
  };
  auto options = std::make_shared<ConvertOptions>();
  auto* command = app.add_subcommand(
      "convert", "Validate a mesh and write it in another format (OBJ, OFF, PLY), vertex order kept");
  command->add_option("MESH", options->input, "Input mesh file")->required();
  command->add_option("-o,--output", options->output, "Output mesh file; its extension picks the format")
      ->required();
  command->callback([options, &exit_status] {
    exit_status = run_guarded([&] {
      std::vector<std::string> warnings;
      const Mesh mesh = read_mesh(options->input, &warnings);
      print_warnings(warnings);
      write_mesh(options->output, mesh);
      std::cout << "wrote " << options->output << " (" << mesh.vertices.rows() << " vertices, "
                << mesh.faces.rows() << " faces)\n";
    });
  });
}

}  // namespace posekit::cli
