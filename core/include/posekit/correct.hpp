// Pose correction by space-time integration: removes the self-intersections of a target pose
// without changing its connectivity, by fitting a smooth space-time vector field to the vertex
// trajectories from a reference pose to the target and integrating the reference through it.
#pragma once

#include <posekit/device.hpp>
#include <posekit/rbf_fitting.hpp>

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace posekit {

/// RK45 controls for correction, in the unit-sphere frame: 1e-5 relative and 1e-6 absolute error per
/// step, far below the field's own fitting error, at a third of the field evaluations of tighter ones.
inline Rk45Options correction_integration_defaults() {
  Rk45Options options;
  options.relative_tolerance = 1e-5;
  options.absolute_tolerance = 1e-6;
  return options;
}

/// Parameters of correct_pose(); the fitting defaults are those of the method's authors.
struct CorrectionOptions {
  int key_frames = 11;               ///< poses from reference to target, both included (>= 2)
  int constraint_times = 13;         ///< s + 1 sample times of each trajectory (>= 2)
  int exclusion_rings = 1;           ///< rings around intersecting faces left unconstrained (>= 0)
  int candidates = 1024;             ///< p: worst constraints considered per fitting round
  int centers_per_round = 128;       ///< m: centers added per fitting round
  double error_factor = 1e-4;        ///< eps = error_factor * d, d the reference's bounding-box diagonal
  int max_centers = 30000;           ///< fitting stops here even when eps is not reached
  bool blocked_update = true;        ///< false: refactorize the whole RBF system every round
  std::vector<int> excluded_vertices;  ///< extra vertices kept out of the constraints
  Rk45Options integration = correction_integration_defaults();  ///< RK45 controls, t from 0 to 1
  /// Time enters the field as time_scale * t (>= 0). The authors weigh time like space (1); 0
  /// chooses the root mean square vertex displacement (unit-sphere frame) clamped to [0.05, 1],
  /// which needed up to half the centers on the shared poses.
  double time_scale = 0.0;
  /// Refits with each constrained vertex's endpoint drift added to its velocities, then integrates
  /// again: same centers, two triangular solves and one integration per pass (>= 0).
  int drift_passes = 1;
  /// Poses tested for self-intersections per key-frame interval (>= 1): the key frame and
  /// substeps - 1 poses of the trajectories after it.
  int intersection_substeps = 2;
  bool fallback = true;              ///< restore target regions the field cannot reach (see report)
  /// Where new intersections remain after the fallback, correct the regions around them again, each
  /// as a mesh of its own from the reference's region to the result's (see report).
  bool local_correction = true;
  /// Where new intersections remain after the fallback, move their regions back along their path
  /// lines, relative to the surface around them, to the latest clean time (see report).
  bool rollback = true;
  /// Where new intersections remain after the rollback and the local correction, relax the regions
  /// around them as-rigid-as-possible towards the reference's local shape, their surroundings held
  /// in place: it undoes folds (see report).
  bool relaxation = true;
  /// Where new intersections remain after all that, correct in two legs through the pose halfway in
  /// edge space (interpolate_poses, edge method): the reference to that pose, then the corrected
  /// halfway pose to the target; the better result is kept (see report).
  bool intermediate_pose = true;
  /// Where the result still has new intersections, or its median distance to the target is above
  /// `separation_tolerance` of the reference's bounding-box diagonal (the correction moved most of
  /// the pose), the target's own contacts are separated instead: each part pushed back into itself
  /// where it lies in another, its surroundings following as-rigidly-as-possible, folds relaxed.
  /// The better of the two is kept: fewer new intersecting faces, then nearer the target (see report).
  /// Not with reproduction_rings < 0, which asks for the integrated result.
  bool contact_separation = true;
  double separation_tolerance = 1e-3;  ///< > 0, see contact_separation
  /// Which constraints an intersection removes. < 0: a vertex near an intersection in any key frame
  /// loses its whole trajectory, as the authors do. >= 0: only its constraints within this many
  /// key-frame spacings of a frame where it is near one; it keeps the rest of its path, which holds
  /// fast-moving parts in shape, at up to twice the centers.
  double exclusion_window = -1.0;
  /// Reproduction of the target: the integrated result is kept within `reproduction_rings` rings of
  /// the vertices near an intersection in some key frame (the reference's own included) and blended
  /// into the target over `blend_rings` more; elsewhere the result is the target itself, without the
  /// field's fitting error and drift. < 0 keeps the integrated pose everywhere (the authors'
  /// result). Where the blend would make faces intersect, the integrated result is kept around them
  /// too (up to four rounds; then reproduction is skipped). After the last stage a final
  /// reproduction keeps the result only on the faces that intersect in the target (not in the
  /// reference) and those still new, blended over `blend_rings`, widened a ring at a time around
  /// what the blend would make intersect (up to twelve rounds).
  int reproduction_rings = 3;
  int blend_rings = 3;               ///< >= 0, see reproduction_rings
};

/// Wall time of each stage, in seconds.
struct CorrectionTimes {
  double normalization = 0, key_frames = 0, classification = 0, constraints = 0, fitting = 0,
         integration = 0, drift_compensation = 0, reproduction = 0, verification = 0,
         local_correction = 0, rollback = 0, relaxation = 0, halfway = 0, separation = 0, total = 0;
};

/// Median and largest distance between corresponding rows of two poses (in correction reports: the
/// constrained vertices' endpoint drift, in the unit-sphere frame).
struct DriftSummary {
  double median = 0;
  double max = 0;
  /// Of #N by 3 differences; zeros for N = 0.
  static DriftSummary of(const Eigen::MatrixX3d& differences);
};

/// Endpoint drift before and after drift compensation.
struct DriftReport {
  DriftSummary before;
  DriftSummary after;
};

/// What correct_pose() did and how well.
struct CorrectionReport {
  int vertices = 0;
  int faces = 0;
  int excluded_vertices = 0;        ///< vertices kept out of the constraints
  int constraints = 0;              ///< space-time constraints the field was fitted to
  RbfFitReport fit;                 ///< rounds, centers, final maximum squared error
  double fit_tolerance = 0;         ///< eps in normalized units
  double time_scale = 0;            ///< the weight of time used
  Rk45Summary integration;          ///< steps, rejected steps, failures (of the last integration)
  DriftReport drift;
  int reference_intersecting_faces = 0;
  int target_intersecting_faces = 0;
  int result_intersecting_faces = 0;
  int new_intersecting_faces = 0;   ///< in the result but not in the reference
  int integrated_new_intersecting_faces = 0;  ///< new intersecting faces before the fallback
  int fallback_regions = 0;         ///< regions taken from the target
  int fallback_global_regions = 0;  ///< of those, where key frames pass one part through another
  int fallback_smoothed_regions = 0;  ///< small regions smoothed where the target's shape did not help
  int fallback_vertices = 0;        ///< vertices taken from the target or smoothed
  int reproduced_vertices = 0;      ///< vertices given the target's position exactly (0 when skipped)
  bool reproduction_skipped = false;  ///< every margin tried would have added intersecting faces
  /// Vertices given the target's position by the final reproduction, which keeps the result only
  /// around the target's own intersections and what is still new (0 when it found no blend).
  int final_reproduced_vertices = 0;
  std::string fallback_note;        ///< what the fallback did, empty when it did nothing
  int local_new_faces_before = 0;   ///< new intersecting faces when the local correction began (0: it did not run)
  int local_regions = 0;            ///< regions corrected anew on their own
  int local_vertices = 0;           ///< vertices so changed
  /// The result is the local correction of the target itself (of its own entangled regions), which
  /// was better than the correction of the integrated result.
  bool local_from_target = false;
  int relaxation_new_faces_before = 0;  ///< new intersecting faces when the relaxation began (0: it did not run)
  int relaxation_regions = 0;       ///< regions relaxed towards the reference's local shape
  int relaxation_vertices = 0;      ///< vertices so moved
  bool halfway_tried = false;       ///< the two legs through the halfway pose were corrected
  int halfway_new_faces = 0;        ///< new intersecting faces of the corrected halfway pose
  bool through_halfway = false;     ///< the result is the two legs', which was better
  bool separation_tried = false;    ///< the target's contacts were separated (see contact_separation)
  int separation_new_faces = 0;     ///< new intersecting faces of the separated target
  int separation_rounds = 0;        ///< push and relaxation rounds it ran
  bool separated = false;           ///< the result is the separated target, which was better
  int rollback_new_faces_before = 0;  ///< new intersecting faces when the rollback began (0: it did not run)
  int rollback_regions = 0;         ///< regions moved back along their path lines
  int rollback_vertices = 0;        ///< vertices so moved (blend included; summed over the two rounds)
  double rollback_earliest_time = 1;  ///< the earliest time a region was moved back to (1: none)
  double median_distance_to_target = 0;  ///< in the input's units
  double max_distance_to_target = 0;
  int near_intersection_vertices = 0;    ///< vertices near an intersection in some key frame
  double median_distance_near_intersections = 0;  ///< of those alone, in the input's units
  double bounding_box_diagonal = 0;      ///< of the reference, in the input's units
  /// Faces of the result with an edge more than twice as long as in both the reference and the
  /// target (edge_stretch): where the correction stretched the surface rather than moved it.
  int stretched_faces = 0;
  double largest_stretch = 0;            ///< the largest edge_stretch of a face
  std::string device;
  CorrectionTimes seconds;
};

/// Receives a stage name and its fraction done (0 at its start, 1 at its end).
using CorrectionProgress = std::function<void(const std::string& stage, double fraction)>;

/// Corrects `target` (#V by 3) against the clean `reference` (#V by 3) sharing the #F by 3 `faces`:
/// returns the corrected #V by 3 pose. Throws ArgumentError for inconsistent input or options.
Eigen::MatrixX3d correct_pose(const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& target,
                              const Eigen::MatrixX3i& faces, Device& device,
                              const CorrectionOptions& options = {}, CorrectionReport* report = nullptr,
                              const CorrectionProgress& progress = {});

}  // namespace posekit
