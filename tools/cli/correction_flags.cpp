#include "correction_flags.hpp"

#include <posekit/error.hpp>
#include <posekit/integer_list.hpp>

namespace posekit::cli {

void add_correction_flags(CLI::App* command, CorrectionFlags& flags) {
  CorrectionOptions& c = flags.correction;
  command->add_option("--device", flags.device, "Compute device: auto, cpu, opencl, vulkan or cuda")
      ->capture_default_str();
  command->add_option("--exclude", flags.exclude,
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
  command->add_flag("--full-refactorization", flags.full_refactorization,
                    "Refactorize the whole RBF system every round instead of the blocked update");
  command->add_flag("--whole-mesh", c.whole_mesh,
                    "Fit one field to every vertex (the published method) instead of one per region of interest");
  command->add_option("--collar-rings", c.collar_rings,
                      "Rings of constrained vertices around each region of interest that pin its field")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_flag("--progress", flags.progress_lines,
                    "Print a line per finished stage on stderr (always on a terminal)");
  for (const RepairStageInfo& stage : repair_stages()) {
    if (!stage.optional) continue;
    command->add_flag("--no-" + stage.name, flags.skipped_stages[stage.name], "Skip the stage that would " + stage.summary);
  }
}

CorrectionOptions correction_options(const CorrectionFlags& flags, int vertex_count) {
  CorrectionOptions options = flags.correction;
  if (!flags.exclude.empty()) {
    // Vertex indices separated by white space; '#' starts a comment.
    options.excluded_vertices = read_integer_list(flags.exclude, "vertex index", 0, vertex_count);
    if (options.excluded_vertices.empty()) throw InputError(flags.exclude, 0, "the exclusion file lists no vertex");
  }
  options.blocked_update = !flags.full_refactorization;
  for (const auto& [stage, skipped] : flags.skipped_stages) {
    if (skipped) options.disabled_stages.push_back(stage);
  }
  return options;
}

}  // namespace posekit::cli
