#include "cli_common.hpp"
#include "commands.hpp"
#include "progress_line.hpp"

#include <posekit/correct.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>
#include <posekit/integer_list.hpp>
#include <posekit/mesh_io.hpp>

#include <fstream>
#include <iomanip>
#include <iostream>
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
  bool no_fallback = false;
  bool no_rollback = false;
  bool no_local_correction = false;
  bool no_relaxation = false;
  bool no_halfway = false;
  bool no_contact_separation = false;
  CorrectionOptions correction;
};

// Vertex indices separated by white space; '#' starts a comment.
std::vector<int> read_vertex_list(const std::string& file, int vertex_count) {
  std::vector<int> vertices = read_integer_list(file, "vertex index", 0, vertex_count);
  if (vertices.empty()) throw InputError(file, 0, "the exclusion file lists no vertex");
  return vertices;
}

nlohmann::json to_json(const CorrectionReport& report) {
  nlohmann::json rounds = nlohmann::json::array();
  for (const RbfFitRound& round : report.fit.rounds) {
    rounds.push_back({{"centers", round.centers},
                      {"max_squared_error", round.max_squared_error},
                      {"assembly_seconds", round.assembly_seconds},
                      {"factorization_seconds", round.factorization_seconds},
                      {"evaluation_seconds", round.evaluation_seconds}});
  }
  return {
      {"device", report.device},
      {"vertices", report.vertices},
      {"faces", report.faces},
      {"excluded_vertices", report.excluded_vertices},
      {"constraints", report.constraints},
      {"fit",
       {{"rounds", report.fit.rounds.size()},
        {"centers", report.fit.centers},
        {"max_squared_error", report.fit.max_squared_error},
        {"tolerance", report.fit_tolerance},
        {"converged", report.fit.converged},
        {"per_round", rounds}}},
      {"rk45",
       {{"accepted_steps", report.integration.accepted_steps},
        {"rejected_steps", report.integration.rejected_steps},
        {"rhs_evaluations", report.integration.rhs_evaluations},
        {"failures", report.integration.failures}}},
      {"intersecting_faces",
       {{"reference", report.reference_intersecting_faces},
        {"target", report.target_intersecting_faces},
        {"result", report.result_intersecting_faces},
        {"new_in_result", report.new_intersecting_faces}}},
      {"fallback",
       {{"new_faces_after_integration", report.integrated_new_intersecting_faces},
        {"regions", report.fallback_regions},
        {"global_regions", report.fallback_global_regions},
        {"smoothed_regions", report.fallback_smoothed_regions},
        {"vertices", report.fallback_vertices},
        {"note", report.fallback_note}}},
      {"reproduction",
       {{"vertices", report.reproduced_vertices},
        {"skipped", report.reproduction_skipped},
        {"final_vertices", report.final_reproduced_vertices}}},
      {"local_correction",
       {{"new_faces_before", report.local_new_faces_before},
        {"regions", report.local_regions},
        {"vertices", report.local_vertices},
        {"from_target", report.local_from_target}}},
      {"halfway",
       {{"tried", report.halfway_tried},
        {"new_faces", report.halfway_new_faces},
        {"used", report.through_halfway}}},
      {"contact_separation",
       {{"tried", report.separation_tried},
        {"new_faces", report.separation_new_faces},
        {"rounds", report.separation_rounds},
        {"used", report.separated}}},
      {"relaxation",
       {{"new_faces_before", report.relaxation_new_faces_before},
        {"regions", report.relaxation_regions},
        {"vertices", report.relaxation_vertices}}},
      {"rollback",
       {{"new_faces_before", report.rollback_new_faces_before},
        {"regions", report.rollback_regions},
        {"vertices", report.rollback_vertices},
        {"earliest_time", report.rollback_earliest_time}}},
      {"distance_to_target",
       {{"median", report.median_distance_to_target},
        {"max", report.max_distance_to_target},
        {"near_intersection_vertices", report.near_intersection_vertices},
        {"median_near_intersections", report.median_distance_near_intersections},
        {"bounding_box_diagonal", report.bounding_box_diagonal}}},
      {"distortion",
       {{"stretched_faces", report.stretched_faces},
        {"largest_stretch", report.largest_stretch}}},
      {"time_scale", report.time_scale},
      {"drift",
       {{"before", {{"median", report.drift.before.median}, {"max", report.drift.before.max}}},
        {"after", {{"median", report.drift.after.median}, {"max", report.drift.after.max}}}}},
      {"seconds",
       {{"normalization", report.seconds.normalization},
        {"key_frames", report.seconds.key_frames},
        {"classification", report.seconds.classification},
        {"constraints", report.seconds.constraints},
        {"fitting", report.seconds.fitting},
        {"integration", report.seconds.integration},
        {"drift_compensation", report.seconds.drift_compensation},
        {"reproduction", report.seconds.reproduction},
        {"verification", report.seconds.verification},
        {"local_correction", report.seconds.local_correction},
        {"rollback", report.seconds.rollback},
        {"relaxation", report.seconds.relaxation},
        {"halfway", report.seconds.halfway},
        {"contact_separation", report.seconds.separation},
        {"total", report.seconds.total}}},
  };
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
  options.correction.fallback = !options.no_fallback;
  options.correction.rollback = !options.no_rollback;
  options.correction.local_correction = !options.no_local_correction;
  options.correction.relaxation = !options.no_relaxation;
  options.correction.intermediate_pose = !options.no_halfway;
  options.correction.contact_separation = !options.no_contact_separation;
  std::unique_ptr<Device> device = create_device(options.device);

  CorrectionReport report;
  ProgressLine progress("correct");
  const Eigen::MatrixX3d corrected = correct_pose(reference.vertices, target.vertices, reference.faces, *device,
                                                  options.correction, &report, progress.callback());
  progress.finish();
  write_mesh(options.output, Mesh{corrected, reference.faces});
  if (!options.report.empty()) write_text_atomically(options.report, to_json(report).dump(2) + "\n");

  std::cout << std::fixed << std::setprecision(2) << options.output << ": intersecting faces "
            << report.target_intersecting_faces << " in the target, " << report.result_intersecting_faces
            << " in the result (" << report.new_intersecting_faces << " not in the reference); " << report.fit.centers
            << " centers, " << report.seconds.total << " s on " << report.device << "\n";
  if (!report.fit.converged) {
    std::cerr << "posekit: warning: the field did not reach the error bound within " << options.correction.max_centers
              << " centers\n";
  }
  if (!report.fallback_note.empty()) std::cerr << "posekit: note: " << report.fallback_note << "\n";
  if (report.local_regions > 0) {
    std::cerr << "posekit: note: " << report.local_regions << " region(s) (" << report.local_vertices
              << " vertices) " << (report.local_from_target ? "of the target corrected on their own, in place of the integrated result; " : "corrected again on their own; ")
              << report.local_new_faces_before << " new intersecting faces before\n";
  }
  if (report.through_halfway) {
    std::cerr << "posekit: note: corrected in two legs through the pose halfway in edge space ("
              << report.halfway_new_faces << " new intersecting faces there after its correction)\n";
  }
  if (report.separated) {
    std::cerr << "posekit: note: the result is the target with its own contacts separated, which was nearer the "
                 "target than the field's correction ("
              << report.separation_rounds << " rounds)\n";
  }
  if (report.relaxation_regions > 0) {
    std::cerr << "posekit: note: " << report.relaxation_regions << " folded region(s) (" << report.relaxation_vertices
              << " vertices) relaxed towards the reference's shape; " << report.relaxation_new_faces_before
              << " new intersecting faces before\n";
  }
  if (report.rollback_regions > 0) {
    std::cerr << "posekit: note: " << report.rollback_regions << " region(s) (" << report.rollback_vertices
              << " vertices) moved back along their path lines, to time " << report.rollback_earliest_time
              << " at the earliest; " << report.rollback_new_faces_before << " new intersecting faces before, "
              << report.new_intersecting_faces << " after\n";
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
  command->add_flag("--no-fallback", options->no_fallback,
                    "Keep the integrated result where it has intersections the reference has not");
  command->add_flag("--no-local-correction", options->no_local_correction,
                    "Do not correct regions that still intersect again on their own");
  command->add_flag("--no-rollback", options->no_rollback,
                    "Do not move regions that still intersect back along their path lines");
  command->add_flag("--no-halfway", options->no_halfway,
                    "Do not try the correction in two legs through the halfway pose where faces remain");
  command->add_flag("--no-contact-separation", options->no_contact_separation,
                    "Do not try separating the target's own contacts where the correction strays from the target");
  command->add_flag("--no-relaxation", options->no_relaxation,
                    "Do not relax folded regions that still intersect towards the reference's shape");
  command->callback([options, &exit_status] { exit_status = run_guarded([&] { run_correct(*options); }); });
}

}  // namespace posekit::cli
