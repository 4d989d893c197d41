// Pose correction by space-time integration: removes the self-intersections of a target pose
// without changing its connectivity, by fitting a smooth space-time vector field to the vertex
// trajectories from a reference pose to the target and integrating the reference through it.
// What the field leaves is repaired by a ladder of stages (repair_stages()); docs/correct.md
// describes the method, every option and the report.
#pragma once

#include <posekit/device.hpp>
#include <posekit/rbf_fitting.hpp>

#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace posekit {

/// RK45 controls for correction, in the unit-sphere frame: 1e-5 relative and 1e-6 absolute error per
/// step, far below the field's own fitting error, at a third of the field evaluations of tighter ones.
/// correct_pose() integrates from 0 to the time scale; the positions are in the unit-sphere frame.
inline Rk45StepControl correction_integration_defaults() {
  Rk45StepControl options;
  options.relative_tolerance = 1e-5;
  options.absolute_tolerance = 1e-6;
  return options;
}

/// Parameters of correct_pose(); the fitting defaults are those of the method's authors.
struct CorrectionOptions {
  int key_frames = 11;               ///< poses from reference to target, both included (>= 2)
  int constraint_times = 13;         ///< s + 1 sample times of each trajectory (>= 2)
  int exclusion_rings = 1;           ///< rings around intersecting faces left unconstrained (>= 0)
  int candidates = 1024;             ///< p: worst constraints considered per fitting round (>= 1)
  int centers_per_round = 128;       ///< m: centers added per fitting round (>= 1)
  /// eps = error_factor * d, d the reference's bounding-box diagonal in the unit-sphere frame (> 0):
  /// the fit stops when every constraint's squared velocity error |f(y) - v|^2, in that frame and
  /// with time scaled (see time_scale), is below eps / time_scale^2.
  double error_factor = 1e-4;
  int max_centers = 30000;           ///< fitting stops here even when eps is not reached (>= 17)
  bool blocked_update = true;        ///< false: refactorize the whole RBF system every round
  std::vector<int> excluded_vertices;  ///< extra vertices kept out of the constraints
  /// RK45 tolerances and step limits of the integration through the field, over the whole motion.
  Rk45StepControl integration = correction_integration_defaults();
  /// Time enters the field as time_scale * t (>= 0). The authors weigh time like space (1); 0
  /// chooses the root mean square vertex displacement (unit-sphere frame) of the field's region,
  /// clamped to [0.05, 1], which needed up to half the centers on the shared poses.
  double time_scale = 0.0;
  /// Refits with each constrained vertex's endpoint drift added to its velocities, then integrates
  /// again: same centers, two triangular solves and one integration per pass (>= 0). Only the last
  /// integration takes the whole region; those before it take the vertices whose drift they measure.
  int drift_passes = 1;
  /// Poses tested for self-intersections per key-frame interval (>= 1): the key frame and
  /// substeps - 1 poses of the trajectories after it.
  int intersection_substeps = 2;
  /// Which constraints an intersection removes. < 0: a vertex near an intersection in any key frame
  /// loses its whole trajectory, as the authors do. >= 0: only its constraints within this many
  /// key-frame spacings of a frame where it is near one; it keeps the rest of its path, which holds
  /// fast-moving parts in shape, at up to twice the centers.
  double exclusion_window = -1.0;
  /// Where the field is fitted. false: one field per region of interest, the vertices near an
  /// intersection in some tested pose with `collar_rings` rings of constrained vertices around
  /// them; regions whose faces intersect each other in some tested pose are one region, and every
  /// vertex outside a region stays at the target. true: one field for every vertex, the authors'
  /// method. The repair stages are the same.
  bool whole_mesh = false;
  /// Rings of constrained vertices around each region's unconstrained ones that pin its field
  /// (>= 1; docs/correct.md tells how the default was measured). Where faces remain, the
  /// `wider-collar` stage corrects again with 8.
  int collar_rings = 3;
  /// Reproduction of the target: the integrated result is kept within `reproduction_rings` rings of
  /// the vertices near an intersection in some tested pose (the reference's own included) and
  /// blended into the target over `blend_rings` more; elsewhere the result is the target itself,
  /// without the field's fitting error and drift. < 0 keeps the integrated pose everywhere (the
  /// authors' result; the final reproduction and the contact separation then do not run). Where the
  /// blend would make faces intersect, the integrated result is kept around them too (up to four
  /// rounds; then reproduction is skipped).
  int reproduction_rings = 3;
  int blend_rings = 3;               ///< rings over which a kept region fades into the target (>= 0)
  /// A candidate whose median distance to the target is within this fraction of the reference's
  /// bounding-box diagonal counts as near the target (> 0): the repair ladder prefers a near
  /// candidate to a less stretched one, and separates the target's contacts where the candidate is
  /// not near.
  double separation_tolerance = 1e-3;
  /// Repair stages that do not run, by name (see repair_stages(); all but the field correction
  /// may be named). An unknown name is an ArgumentError.
  std::vector<std::string> disabled_stages;
};

/// One stage of correct_pose()'s repair ladder, as the report, the command line and the progress
/// callback name it.
struct RepairStageInfo {
  std::string name;      ///< e.g. "rollback": its report entry and the command line's --no-rollback
  std::string summary;   ///< what it does, in one line
  bool optional = true;  ///< may be disabled (every stage but the field correction)
};

/// The stages of correct_pose()'s repair ladder in the order they run, each name once (a stage
/// that runs twice is listed where it first runs).
const std::vector<RepairStageInfo>& repair_stages();

/// Median and largest distance between corresponding rows of two poses (in correction reports: the
/// constrained vertices' endpoint drift, in the unit-sphere frame).
struct DriftSummary {
  double median = 0;
  double max = 0;
  /// Of #N by 3 differences; zeros for N = 0.
  static DriftSummary of(const Eigen::Ref<const Eigen::MatrixX3d>& differences);
};

/// Endpoint drift before and after drift compensation.
struct DriftReport {
  DriftSummary before;
  DriftSummary after;
};

/// One field of the field correction: its region, its fit and its integration.
struct FieldRegionReport {
  int vertices = 0;                ///< vertices of the region, collar included
  int unconstrained_vertices = 0;  ///< of those, kept out of the constraints
  int constraints = 0;             ///< space-time constraints the field was fitted to
  double time_scale = 0;           ///< the weight of time used
  RbfFitReport fit;                ///< rounds, centers, final maximum squared error
  Rk45Summary integration;         ///< steps, rejected steps, failures (of the last integration)
  DriftReport drift;               ///< endpoint drift of the constrained vertices (unit-sphere frame)
};

/// Wall time of the field correction's steps, in seconds.
struct FieldTimes {
  double normalization = 0, key_frames = 0, classification = 0, regions = 0, fitting = 0, integration = 0,
         drift_compensation = 0, reproduction = 0;
};

/// What the field correction did: key frames, classification, regions, fits, integration, drift.
struct FieldReport {
  int key_frames = 0;
  int tested_poses = 0;                 ///< poses tested for self-intersections
  int reference_intersecting_faces = 0;
  int target_intersecting_faces = 0;
  int excluded_vertices = 0;            ///< vertices kept out of the constraints
  int near_intersection_vertices = 0;   ///< near an intersection in some tested pose, or excluded
  bool whole_mesh = false;              ///< one field for every vertex (CorrectionOptions::whole_mesh)
  int collar_rings = 0;                 ///< constrained rings around each region's unconstrained vertices
  int region_vertices = 0;              ///< vertices in some region
  std::vector<FieldRegionReport> regions;  ///< one per field, largest first
  double fit_tolerance = 0;             ///< eps in the unit-sphere frame
  int new_faces_after_integration = 0;  ///< new intersecting faces of the integrated pose
  int reproduced_vertices = 0;          ///< vertices given the target's position by reproduction
  bool reproduction_skipped = false;    ///< every margin tried would have added intersecting faces
  FieldTimes seconds;
  int constraints() const;              ///< over all regions
  int centers() const;                  ///< over all regions
  bool converged() const;               ///< every region's fit reached eps
};

/// What one stage of the repair ladder did.
struct StageReport {
  std::string name;             ///< as in repair_stages()
  bool ran = false;
  /// Why it did not run: "disabled", "nested run", "nothing to repair" or "unchanged since it ran" (a
  /// stage of its repair already ran on the same candidate or made it).
  std::string skipped;
  bool kept = false;            ///< its pose replaced the candidate: fewer new faces, or as many and nearer the target
  int new_faces_before = 0;     ///< new intersecting faces of the candidate it started from
  int new_faces_after = 0;      ///< and of the candidate after it
  int regions = 0;              ///< regions it changed
  int vertices = 0;             ///< vertices it moved, each counted once
  double seconds = 0;
  std::string note;             ///< what it did, in words, when its pose was kept
  std::vector<std::pair<std::string, double>> details;  ///< its own figures, by name (docs/correct.md)
};

/// How the result compares with the reference and the target.
struct ResultReport {
  int reference_intersecting_faces = 0;
  int target_intersecting_faces = 0;
  int intersecting_faces = 0;       ///< of the result
  int new_intersecting_faces = 0;   ///< of the result and not of the reference: the goal is 0
  double median_distance_to_target = 0;  ///< in the input's units
  double max_distance_to_target = 0;
  int near_intersection_vertices = 0;    ///< near an intersection in some tested pose
  double median_distance_near_intersections = 0;  ///< of those alone, in the input's units
  int changed_vertices = 0;         ///< vertices not exactly at the target
  double bounding_box_diagonal = 0; ///< of the reference, in the input's units
  /// Faces with an edge more than twice as long as in both the reference and the target
  /// (edge_stretch; edges shorter than a quarter of the mean count as that long): where the
  /// correction stretched the surface rather than moved it.
  int stretched_faces = 0;
  int strongly_stretched_faces = 0; ///< of those, with an edge more than three times as long
  double largest_stretch = 0;       ///< the largest edge_stretch of a face
};

/// What correct_pose() did and how well.
struct CorrectionReport {
  int vertices = 0;
  int faces = 0;
  std::string device;
  FieldReport field;
  std::vector<StageReport> stages;  ///< every stage of the ladder in order, run or not
  ResultReport result;
  double seconds = 0;               ///< wall time of the whole correction
  /// The last entry of the stage named `name`; nullptr when there is none.
  const StageReport* stage(const std::string& name) const;
};

/// Receives a stage name and its fraction done (0 at its start, 1 at its end): the field
/// correction's steps ("key frames", "classification", "fitting", ...) and each repair stage.
using CorrectionProgress = std::function<void(const std::string& stage, double fraction)>;

/// Corrects `target` (#V by 3) against the clean `reference` (#V by 3) sharing the #F by 3 `faces`:
/// returns the corrected #V by 3 pose. Throws ArgumentError for inconsistent input or options.
/// While it runs, Eigen's cache sizes are fixed process-wide (Eigen::setCpuCacheSizes: 48 KiB, 512
/// KiB, 32 MiB; the caller's come back after), so that the CPU device gives the same bits on every
/// x86-64 processor with AVX2 and FMA.
Eigen::MatrixX3d correct_pose(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                              const Eigen::Ref<const Eigen::MatrixX3d>& target,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                              Device& device, const CorrectionOptions& options = {},
                              CorrectionReport* report = nullptr, const CorrectionProgress& progress = {});

}  // namespace posekit
