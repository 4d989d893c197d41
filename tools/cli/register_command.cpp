#include "blend_common.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "html_page.hpp"
#include "html_report_option.hpp"
#include "job_pages.hpp"

#include <posekit/error.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/partial_registration.hpp>

#include <chrono>
#include <iomanip>
#include <iostream>

namespace posekit::cli {
namespace {

struct RegisterCommandOptions {
  BlendCommandOptions blend;
  std::string scan;
  std::string features;
  std::string output;
  std::string report;
  std::string html;
  ScanFitOptions fit;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void run_register(RegisterCommandOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  mesh_format_from_extension(options.output);
  if (!options.html.empty()) report::check_report_destination(options.html, "--html");
  const PoseSet examples = read_examples(options.blend);
  std::vector<std::string> warnings;
  const Mesh scan = read_mesh(options.scan, &warnings);
  print_warnings(warnings);
  PointConstraints features = read_point_constraints(options.features, examples.vertex_count());
  const double reading = seconds_since(start);

  BlendedDeformer deformer = make_deformer(examples, options.blend);
  nlohmann::json report;
  // Ambiguous features are resolved first, by the energy of the deformation they give alone.
  if (std::any_of(features.groups.begin(), features.groups.end(), [](const std::string& g) { return !g.empty(); })) {
    deform_to_points(deformer, features, report);
  }
  const ScanRegistration registration =
      register_partial_scan(deformer, scan, features.vertices, features.positions, options.fit);
  write_mesh(options.output, Mesh{registration.deformation.vertices, examples.faces()});

  registration_json(registration, examples, deformer, report);
  report["features"] = features.vertices.size();
  const Eigen::VectorXd& d = registration.distances;
  report["examples"] = options.blend.examples;
  report["reference"] = options.blend.examples.front();
  report["scan"] = {{"file", options.scan}, {"vertices", scan.vertices.rows()}, {"faces", scan.faces.rows()}};
  report["seconds"] = {{"reading", reading},
                       {"setup", deformer.setup_report().seconds.total},
                       {"registration", registration.seconds},
                       {"total", seconds_since(start)}};
  if (!options.report.empty()) write_text_atomically(options.report, report.dump(1) + "\n");
  if (!options.html.empty()) {
    report::write_html_report(options.html, report::registration_page(examples.pose(0), registration.deformation.vertices,
                                                                      examples.faces(), scan.vertices, features,
                                                                      command_line()));
  }
  std::cout << std::setprecision(4) << options.output << ": fitted to " << scan.vertices.rows() << " scan vertices ("
            << features.vertices.size() << " features, " << registration.iterations.size()
            << " ICP rounds), scale " << registration.deformation.scale << ", max scan distance " << d.maxCoeff()
            << ", " << std::setprecision(3) << registration.seconds << " s\n";
}

}  // namespace

void add_register_command(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<RegisterCommandOptions>();
  auto* command = app.add_subcommand(
      "register", "Complete a partial scan: fit the full mesh of the examples to it and match its points");
  add_blend_options(command, options->blend);
  command->add_option("--scan", options->scan, "Partial scan, a triangle mesh (OBJ, OFF or PLY)")->required();
  command->add_option("--features", options->features,
                      "Text file, one 'VERTEX X Y Z [GROUP]' per line: a mesh vertex and its position on the scan")
      ->required();
  command->add_option("-o,--output", options->output, "Fitted full mesh (OBJ, OFF or PLY)")->required();
  command->add_option("--report", options->report,
                      "Write a JSON report (with the mesh vertex matched to every scan vertex) to this file");
  add_html_option(command, options->html);
  add_scan_fit_options(command, options->fit);
  command->callback([options, &exit_status] { exit_status = run_guarded([&] { run_register(*options); }); });
}

}  // namespace posekit::cli
