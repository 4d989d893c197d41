#include "cli_common.hpp"
#include "commands.hpp"
#include "correction_flags.hpp"
#include "correction_report_json.hpp"
#include "html_report_option.hpp"
#include "progress_line.hpp"

#include "html_page.hpp"
#include "job_pages.hpp"

#include <posekit/correct.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/mesh_io.hpp>

#include <iomanip>
#include <iostream>

namespace posekit::cli {
namespace {

struct CorrectCommandOptions {
  std::string reference;
  std::string target;
  std::string output;
  std::string report;
  std::string html;
  CorrectionFlags flags;
};

void run_correct(const CorrectCommandOptions& options) {
  if (!options.html.empty()) report::check_report_destination(options.html, "--html");
  std::vector<std::string> warnings;
  const Mesh reference = read_mesh(options.reference, &warnings);
  const Mesh target = read_mesh(options.target, &warnings);
  check_same_connectivity(reference, options.reference, target, options.target);
  print_warnings(warnings);
  const CorrectionOptions correction = correction_options(options.flags, static_cast<int>(reference.vertices.rows()));
  std::unique_ptr<Device> device = create_device(options.flags.device);
  CorrectionReport report;
  ProgressLine progress("correct", options.flags.progress_lines);
  const Eigen::MatrixX3d corrected = correct_pose(reference.vertices, target.vertices, reference.faces, *device,
                                                  correction, &report, progress.callback());
  progress.finish();
  write_mesh(options.output, Mesh{corrected, reference.faces});
  if (!options.report.empty()) write_text_atomically(options.report, correction_report_json(report).dump(2) + "\n");
  if (!options.html.empty()) {
    report::write_html_report(options.html, report::correction_page(reference.vertices, target.vertices, corrected,
                                                                    reference.faces, report, command_line()));
  }
  std::cout << std::fixed << std::setprecision(2) << options.output << ": intersecting faces "
            << report.result.target_intersecting_faces << " in the target, " << report.result.intersecting_faces
            << " in the result (" << report.result.new_intersecting_faces << " not in the reference); "
            << report.field.centers() << " centers, " << report.seconds << " s on " << report.device << "\n";
  if (!report.field.converged()) {
    std::cerr << "posekit: warning: a field did not reach the error bound within " << correction.max_centers
              << " centers\n";
  }
  for (const StageReport& stage : report.stages) {
    if (stage.kept && !stage.note.empty()) std::cerr << "posekit: note: " << stage.name << ": " << stage.note << "\n";
  }
}

}  // namespace

void add_correct_command(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<CorrectCommandOptions>();
  auto* command = app.add_subcommand(
      "correct", "Remove the self-intersections of TARGET by space-time integration from the clean REFERENCE");
  command->add_option("REFERENCE", options->reference, "Clean reference pose")->required();
  command->add_option("TARGET", options->target, "Pose to correct, same connectivity")->required();
  command->add_option("-o,--output", options->output, "Corrected pose (OBJ, OFF or PLY)")->required();
  command->add_option("--report", options->report, "Write a JSON report to this file");
  add_html_option(command, options->html);
  add_correction_flags(command, options->flags);
  command->callback([options, &exit_status] { exit_status = run_guarded([&] { run_correct(*options); }); });
}

}  // namespace posekit::cli
