#include "cli_common.hpp"
#include "commands.hpp"
#include "correction_report_json.hpp"
#include "progress_line.hpp"

#include <posekit/correct.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>
#include <posekit/integer_list.hpp>
#include <posekit/mesh_io.hpp>

#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace posekit::cli {
namespace {

struct CorrectCommandOptions {
  std::string reference;
  std::string target;
  std::string output;
  std::string device = "auto";
  std::string report;
  std::string exclude;
  bool full_refactorization = false;
  bool progress_lines = false;
  std::map<std::string, bool> skipped_stages;  // --no-<stage>, one per optional repair stage
  CorrectionOptions correction;
};

// Vertex indices separated by white space; '#' starts a comment.
std::vector<int> read_vertex_list(const std::string& file, int vertex_count) {
  std::vector<int> vertices = read_integer_list(file, "vertex index", 0, vertex_count);
  if (vertices.empty()) throw InputError(file, 0, "the exclusion file lists no vertex");
  return vertices;
}

void run_correct(CorrectCommandOptions options) {
  std::vector<std::string> warnings;
  const Mesh reference = read_mesh(options.reference, &warnings);
  const Mesh target = read_mesh(options.target, &warnings);
  check_same_connectivity(reference, options.reference, target, options.target);
  print_warnings(warnings);
  if (!options.exclude.empty()) {
    options.correction.excluded_vertices = read_vertex_list(options.exclude, static_cast<int>(reference.vertices.rows()));
  }
  options.correction.blocked_update = !options.full_refactorization;
  for (const auto& [stage, skipped] : options.skipped_stages) {
    if (skipped) options.correction.disabled_stages.push_back(stage);
  }
  std::unique_ptr<Device> device = create_device(options.device);

  CorrectionReport report;
  ProgressLine progress("correct", options.progress_lines);
  const Eigen::MatrixX3d corrected = correct_pose(reference.vertices, target.vertices, reference.faces, *device,
                                                  options.correction, &report, progress.callback());
  progress.finish();
  write_mesh(options.output, Mesh{corrected, reference.faces});
  if (!options.report.empty()) write_text_atomically(options.report, correction_report_json(report).dump(2) + "\n");

  std::cout << std::fixed << std::setprecision(2) << options.output << ": intersecting faces "
            << report.result.target_intersecting_faces << " in the target, " << report.result.intersecting_faces
            << " in the result (" << report.result.new_intersecting_faces << " not in the reference); "
            << report.field.centers() << " centers, " << report.seconds << " s on " << report.device << "\n";
  if (!report.field.converged()) {
    std::cerr << "posekit: warning: a field did not reach the error bound within " << options.correction.max_centers
              << " centers\n";
  }
  for (const StageReport& stage : report.stages) {
    if (stage.kept && !stage.note.empty()) std::cerr << "posekit: note: " << stage.name << ": " << stage.note << "\n";
  }
}

}  // namespace

void add_correct_command(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<CorrectCommandOptions>();
  CorrectionOptions& c = options->correction;
  auto* command = app.add_subcommand(
      "correct", "Remove the self-intersections of TARGET by space-time integration from the clean REFERENCE");
  command->add_option("REFERENCE", options->reference, "Clean reference pose")->required();
  command->add_option("TARGET", options->target, "Pose to correct, same connectivity")->required();
  command->add_option("-o,--output", options->output, "Corrected pose (OBJ, OFF or PLY)")->required();
  command->add_option("--device", options->device, "Compute device: auto, cpu, opencl, vulkan or cuda")
      ->capture_default_str();
  command->add_option("--report", options->report, "Write a JSON report to this file");
  command->add_option("--exclude", options->exclude,
                      "File of vertex indices to keep out of the constraints (white-space separated)");
  command->add_option("--key-frames", c.key_frames, "Key frames from reference to target, both included")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  command->add_option("--intersection-substeps", c.intersection_substeps,
                      "Poses tested for self-intersections per key-frame interval (the key frame, then the trajectories)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  command->add_option("--constraint-times", c.constraint_times, "Sample times per trajectory (s + 1)")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  command->add_option("--exclusion-rings", c.exclusion_rings, "Rings around intersecting faces left unconstrained")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  command->add_option("--candidates", c.candidates, "p: worst constraints considered per fitting round")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("--centers-per-round", c.centers_per_round, "m: centers added per fitting round")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--error-factor", c.error_factor, "eps = factor * bounding-box diagonal")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--time-scale", c.time_scale,
                      "Weight of time against space in the field's domain (0: the RMS vertex displacement)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--drift-passes", c.drift_passes,
                      "Refits that move the constrained vertices' endpoints back onto the target")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  command->add_option("--exclusion-window", c.exclusion_window,
                      "Drop only the constraints within this many key-frame spacings of an intersection "
                      "(< 0: a vertex near one loses its whole trajectory)")
      ->capture_default_str();
  command->add_option("--reproduction-rings", c.reproduction_rings,
                      "Keep the integrated result this many rings around the unconstrained vertices and the "
                      "target's own positions beyond (< 0: the integrated result everywhere)")
      ->check(CLI::Range(-1, 1000))
      ->capture_default_str();
  command->add_option("--blend-rings", c.blend_rings, "Rings over which the integrated result blends into the target")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  command->add_option("--separation-tolerance", c.separation_tolerance,
                      "Separate the target's own contacts where the corrected pose's median distance to the target "
                      "is above this fraction of the bounding-box diagonal (or new faces remain); keep the better")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--max-centers", c.max_centers, "Upper bound on the number of centers")
      ->check(CLI::Range(17, 10000000))
      ->capture_default_str();
  command->add_option("--rtol", c.integration.relative_tolerance, "RK45 relative tolerance")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--atol", c.integration.absolute_tolerance, "RK45 absolute tolerance")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_flag("--full-refactorization", options->full_refactorization,
                    "Refactorize the whole RBF system every round instead of the blocked update");
  command->add_flag("--whole-mesh", c.whole_mesh,
                    "Fit one field to every vertex (the published method) instead of one per region of interest");
  command->add_option("--collar-rings", c.collar_rings,
                      "Rings of constrained vertices around each region of interest that pin its field")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_flag("--progress", options->progress_lines,
                    "Print a line per finished stage on stderr (always on a terminal)");
  for (const RepairStageInfo& stage : repair_stages()) {
    if (!stage.optional) continue;
    command->add_flag("--no-" + stage.name, options->skipped_stages[stage.name], "Skip the stage that would " + stage.summary);
  }
  command->callback([options, &exit_status] { exit_status = run_guarded([&] { run_correct(*options); }); });
}

}  // namespace posekit::cli
