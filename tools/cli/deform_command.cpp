#include "blend_common.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "html_page.hpp"
#include "html_report_option.hpp"
#include "job_pages.hpp"

#include <posekit/error.hpp>
#include <posekit/mesh_io.hpp>

#include <chrono>
#include <iomanip>
#include <iostream>

namespace posekit::cli {
namespace {

struct DeformCommandOptions {
  BlendCommandOptions blend;
  std::string constraints;
  std::string output;
  std::string report;
  std::string html;
  std::string to;
  int frames = 5;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// OUT with "-NNN" before the extension: the name of interpolation frame `index`.
std::filesystem::path frame_name(const std::filesystem::path& output, int index) {
  std::ostringstream number;
  number << std::setw(3) << std::setfill('0') << index;
  std::filesystem::path name = output;
  name.replace_filename(output.stem().string() + "-" + number.str() + output.extension().string());
  return name;
}

nlohmann::json residual_json(const Eigen::MatrixX3d& vertices, const PointConstraints& constraints) {
  double largest = 0.0;
  double sum = 0.0;
  for (size_t r = 0; r < constraints.vertices.size(); ++r) {
    const double d = (vertices.row(constraints.vertices[r]) - constraints.positions.row(static_cast<Eigen::Index>(r))).norm();
    largest = std::max(largest, d);
    sum += d;
  }
  return {{"max", largest}, {"mean", sum / static_cast<double>(constraints.vertices.size())}};
}

void run_deform(DeformCommandOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  mesh_format_from_extension(options.output);  // a bad output name fails before any work
  if (!options.html.empty()) report::check_report_destination(options.html, "--html");
  if (!options.to.empty() && options.frames < 2) throw ArgumentError("--frames must be at least 2");
  const PoseSet examples = read_examples(options.blend);
  PointConstraints constraints = read_point_constraints(options.constraints, examples.vertex_count());
  PointConstraints second;
  if (!options.to.empty()) second = read_point_constraints(options.to, examples.vertex_count());
  const double reading = seconds_since(start);

  BlendedDeformer deformer = make_deformer(examples, options.blend);
  nlohmann::json report;
  const auto solve_start = std::chrono::steady_clock::now();
  const BlendResult result = deform_to_points(deformer, constraints, report);
  const double solving = seconds_since(solve_start);

  std::vector<std::filesystem::path> written;
  std::vector<Eigen::MatrixX3d> shown;  // for the HTML report
  if (options.to.empty()) {
    write_mesh(options.output, Mesh{result.vertices, examples.faces()});
    written.push_back(options.output);
    shown.push_back(result.vertices);
  } else {
    nlohmann::json second_report;
    const BlendResult end = deform_to_points(deformer, second, second_report);
    report["to"] = deformation_json(end, examples);
    if (second_report.contains("correspondence")) report["to"]["correspondence"] = second_report["correspondence"];
    report["frames"] = options.frames;
    for (int i = 0; i < options.frames; ++i) {
      const double t = static_cast<double>(i) / (options.frames - 1);
      const std::filesystem::path name = frame_name(options.output, i);
      shown.push_back(deformer.interpolate(result, end, t));
      write_mesh(name, Mesh{shown.back(), examples.faces()});
      written.push_back(name);
    }
  }
  report["examples"] = options.blend.examples;
  report["reference"] = options.blend.examples.front();
  report["faces"] = examples.faces().rows();
  report["constraints"] = constraints.vertices.size();
  report["setup"] = setup_json(deformer.setup_report());
  report["deformation"] = deformation_json(result, examples);
  report["constraint_residual"] = residual_json(result.vertices, constraints);
  report["seconds"] = {{"reading", reading},
                       {"setup", deformer.setup_report().seconds.total},
                       {"deformation", solving},
                       {"total", seconds_since(start)}};
  if (!options.report.empty()) write_text_atomically(options.report, report.dump(2) + "\n");
  if (!options.html.empty()) {
    std::vector<std::string> names;
    for (const std::filesystem::path& file : written) names.push_back(file.filename().string());
    std::vector<PointConstraints> sets{constraints};
    if (!options.to.empty()) sets.push_back(second);
    report::write_html_report(options.html, report::deformation_page(examples.pose(0), shown, names, examples.faces(),
                                                                     sets, command_line()));
  }
  std::cout << std::setprecision(4) << written.front().string();
  if (written.size() > 1) std::cout << " .. " << written.back().string();
  std::cout << ": " << constraints.vertices.size() << " constraints, " << examples.pose_count()
            << " examples, scale " << result.scale << ", energy " << result.energy << ", "
            << std::setprecision(3) << 1e3 * result.seconds << " ms per deformation after "
            << deformer.setup_report().seconds.total << " s of precomputation\n";
}

}  // namespace

void add_deform_command(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<DeformCommandOptions>();
  auto* command = app.add_subcommand(
      "deform", "Find a natural pose from a few point constraints, blending the transformations of example poses");
  add_blend_options(command, options->blend);
  command->add_option("--constraints", options->constraints,
                      "Text file, one 'VERTEX X Y Z [GROUP]' per line ('#' comments); vertices sharing a GROUP "
                      "are matched to their positions automatically")
      ->required();
  command->add_option("-o,--output", options->output, "Deformed pose (OBJ, OFF or PLY)")->required();
  command->add_option("--report", options->report, "Write a JSON report to this file");
  add_html_option(command, options->html);
  command->add_option("--to", options->to,
                      "Second constraint file: write --frames poses interpolated from the first deformation to "
                      "this one, named OUT-000.EXT, OUT-001.EXT, ...");
  command->add_option("--frames", options->frames, "Number of interpolated poses, both ends included")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  command->callback([options, &exit_status] { exit_status = run_guarded([&] { run_deform(*options); }); });
}

}  // namespace posekit::cli
