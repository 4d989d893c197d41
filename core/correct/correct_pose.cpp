// The correction pipeline: normalize, key frames, classification, constraints, field fitting,
// integration, verification and the fallback for global intersections.
#include <posekit/correct.hpp>
#include <posekit/error.hpp>
#include <posekit/edge_space.hpp>
#include <posekit/geometry.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/mesh.hpp>
#include <posekit/poisson_interpolation.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include "correct/contact_separation.hpp"
#include "correct/intersection_fallback.hpp"
#include "correct/local_correction.hpp"
#include "correct/region_relaxation.hpp"
#include "correct/target_reproduction.hpp"
#include "correct/time_rollback.hpp"
#include "correct/vertex_classification.hpp"
#include "correct/vertex_trajectories.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>

namespace posekit {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A region whose integrated position strays this far (relative to the reference's diagonal) from
// the target counts as one the field could not reach.
constexpr double kFallbackDeviation = 1e-2;

void check_options(const CorrectionOptions& options) {
  const auto require = [](bool condition, const std::string& message) {
    if (!condition) throw ArgumentError(message);
  };
  require(options.key_frames >= 2, "key_frames must be >= 2, got " + std::to_string(options.key_frames));
  require(options.intersection_substeps >= 1,
          "intersection_substeps must be >= 1, got " + std::to_string(options.intersection_substeps));
  require(options.constraint_times >= 2,
          "constraint_times must be >= 2, got " + std::to_string(options.constraint_times));
  require(options.exclusion_rings >= 0,
          "exclusion_rings must be >= 0, got " + std::to_string(options.exclusion_rings));
  require(std::isfinite(options.time_scale) && options.time_scale >= 0.0,
          "time_scale must be finite and >= 0 (0: automatic), got " + std::to_string(options.time_scale));
  require(options.drift_passes >= 0, "drift_passes must be >= 0, got " + std::to_string(options.drift_passes));
  require(std::isfinite(options.exclusion_window),
          "exclusion_window must be finite (< 0: whole trajectories), got " + std::to_string(options.exclusion_window));
  require(options.blend_rings >= 0, "blend_rings must be >= 0, got " + std::to_string(options.blend_rings));
  require(std::isfinite(options.separation_tolerance) && options.separation_tolerance > 0.0,
          "separation_tolerance must be finite and > 0, got " + std::to_string(options.separation_tolerance));
  require(std::isfinite(options.error_factor) && options.error_factor > 0.0,
          "error_factor must be finite and > 0, got " + std::to_string(options.error_factor));
  validate_rk45_options(options.integration);
}

// An edge this many times as long as in both the reference and the target counts as stretched.
constexpr double kStretchedFactor = 2.0;
// Edges shorter than this fraction of the mean edge length in both count as that long: the shared
// poses have slivers whose edges open from almost nothing to an ordinary length (lion-07: 147 times).
constexpr double kShortestStretchedEdge = 0.25;

// Rounds in which reproduction widens what it keeps of the integrated result before it gives up.
constexpr int kReproductionAttempts = 4;
// The final reproduction starts from the target's intersecting faces alone, so it widens one ring at
// a time around what it would add, for longer (the cat and lion poses needed two to ten rounds).
constexpr int kFinalReproductionAttempts = 12;

// Bounds of the automatic time scale: trajectories that hardly move still need time to count, and
// beyond the authors' equal weighting the fits measured no better.
constexpr double kSmallestTimeScale = 0.05;
constexpr double kLargestTimeScale = 1.0;

// The root mean square distance a vertex travels from the reference to the target (unit-sphere
// frame): with time weighted so, a typical trajectory climbs about as much in time as it moves in
// space. Measured on the shared poses and the demo arm, it needed between about half and about as
// many centers as equal weighting, and no fixed weight did as well across slow and fast motions
// (lion-03 fits best near 0.15, the demo arm near 1). Subtracting the best affine map first, which
// the polynomial part carries, was tried and did worse on lion-05.
double automatic_time_scale(const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& target) {
  const double rms = std::sqrt((target - reference).rowwise().squaredNorm().mean());
  return std::clamp(std::isfinite(rms) ? rms : kLargestTimeScale, kSmallestTimeScale, kLargestTimeScale);
}

// Target minus result at the constrained vertices, in their order.
Eigen::MatrixX3d endpoint_drift(const Eigen::MatrixX3d& result, const Eigen::MatrixX3d& target,
                                const std::vector<int>& vertices) {
  Eigen::MatrixX3d drift(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    drift.row(static_cast<Eigen::Index>(k)) = target.row(vertices[k]) - result.row(vertices[k]);
  }
  return drift;
}

void check_pose(const Eigen::MatrixX3d& pose, const char* name) {
  if (pose.rows() == 0) throw ArgumentError(std::string(name) + " has no vertices");
  for (Eigen::Index v = 0; v < pose.rows(); ++v) {
    if (!pose.row(v).allFinite()) {
      throw ArgumentError(std::string(name) + " vertex " + std::to_string(v) + " has a coordinate that is not finite");
    }
  }
}

// The poses tested for intersections: the key frames and, between each two, `substeps` - 1 poses
// of the trajectories. Between key frames an intersection sweeps a band over the surface that
// the frames alone miss, where a part passing through another would find the other's constraints
// and be dragged along.
std::vector<Eigen::MatrixX3d> tested_poses(const std::vector<Eigen::MatrixX3d>& frames,
                                           const detail::VertexTrajectories& trajectories, int substeps) {
  std::vector<Eigen::MatrixX3d> poses;
  const int intervals = static_cast<int>(frames.size()) - 1;
  for (int i = 0; i <= intervals * substeps; ++i) {
    poses.push_back(i % substeps == 0 ? frames[static_cast<size_t>(i / substeps)]
                                      : trajectories.pose(static_cast<double>(i) / (intervals * substeps)));
  }
  return poses;
}

// Which vertices constrain the field at each of the constraint times: all but the unconstrained
// ones, or, with an exclusion window, all but those near an intersection of a key frame within
// the window (in key-frame spacings) of that time.
std::vector<std::vector<char>> constrained_at_times(const detail::VertexClassification& classification,
                                                    const CorrectionOptions& options) {
  const auto time_count = static_cast<size_t>(options.constraint_times);
  const double window = options.exclusion_window;
  if (window < 0) return std::vector<std::vector<char>>(time_count, classification.constrained);
  const auto frame_count = static_cast<int>(classification.unconstrained_in_frame.size());
  const auto vertex_count = classification.constrained.size();
  std::vector<std::vector<char>> constrained(time_count, std::vector<char>(vertex_count, 1));
  for (size_t step = 0; step < time_count; ++step) {
    const double frame_time = static_cast<double>(step) / static_cast<double>(time_count - 1) * (frame_count - 1);
    for (int frame = 0; frame < frame_count; ++frame) {
      if (std::abs(frame - frame_time) > window * options.intersection_substeps) continue;
      const std::vector<char>& excluded = classification.unconstrained_in_frame[static_cast<size_t>(frame)];
      for (size_t v = 0; v < vertex_count; ++v) {
        if (excluded[v]) constrained[step][v] = 0;
      }
    }
  }
  return constrained;
}

}  // namespace

DriftSummary DriftSummary::of(const Eigen::MatrixX3d& differences) {
  DriftSummary summary;
  if (differences.rows() == 0) return summary;
  Eigen::VectorXd distances = differences.rowwise().norm();
  summary.max = distances.maxCoeff();
  const auto middle = distances.data() + distances.size() / 2;
  std::nth_element(distances.data(), middle, distances.data() + distances.size());
  summary.median = *middle;
  return summary;
}

Eigen::MatrixX3d correct_pose(const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& target,
                              const Eigen::MatrixX3i& faces, Device& device, const CorrectionOptions& options,
                              CorrectionReport* report_out, const CorrectionProgress& progress) {
  const Clock::time_point start = Clock::now();
  check_options(options);
  if (reference.rows() != target.rows()) {
    throw ArgumentError("reference has " + std::to_string(reference.rows()) + " vertices but target has " +
                        std::to_string(target.rows()));
  }
  check_pose(reference, "reference");
  check_pose(target, "target");
  check_face_indices(faces, static_cast<int>(reference.rows()));
  if (faces.rows() == 0) throw ArgumentError("the face list is empty");

  CorrectionReport report;
  report.vertices = static_cast<int>(reference.rows());
  report.faces = static_cast<int>(faces.rows());
  report.device = device.info().backend + ": " + device.info().name;
  report.bounding_box_diagonal = bounding_box_diagonal(reference);
  const auto stage = [&progress](const char* name, double fraction) {
    if (progress) progress(name, fraction);
  };

  Clock::time_point stage_start = Clock::now();
  const UnitSphereNormalization normalization = shared_unit_sphere_normalization({reference, target});
  const Eigen::MatrixX3d reference_n = normalization.apply(reference);
  const Eigen::MatrixX3d target_n = normalization.apply(target);
  report.seconds.normalization = seconds_since(stage_start);

  stage_start = Clock::now();
  stage("key frames", 0.0);
  std::vector<Eigen::MatrixX3d> frames = PoissonInterpolator(reference_n, target_n, faces).key_frames(options.key_frames);
  frames.front() = reference_n;  // exact ends, not the solver's round-off
  frames.back() = target_n;
  report.seconds.key_frames = seconds_since(stage_start);
  stage("key frames", 1.0);

  stage_start = Clock::now();
  stage("classification", 0.0);
  const detail::VertexTrajectories trajectories(frames);
  const detail::VertexClassification classification = detail::classify_vertices(
      tested_poses(frames, trajectories, options.intersection_substeps), faces, options.exclusion_rings,
      options.excluded_vertices);
  report.excluded_vertices = classification.excluded;
  report.reference_intersecting_faces = static_cast<int>(classification.reference_intersecting.size());
  report.target_intersecting_faces = static_cast<int>(classification.target_intersecting.size());
  report.seconds.classification = seconds_since(stage_start);
  stage("classification", 1.0);

  frames.clear();
  stage_start = Clock::now();
  const detail::SpaceTimeConstraints constraints =
      detail::sample_constraints(trajectories, constrained_at_times(classification, options));
  report.constraints = static_cast<int>(constraints.positions.rows());
  report.seconds.constraints = seconds_since(stage_start);

  stage_start = Clock::now();
  stage("fitting", 0.0);
  RbfFitOptions fit_options;
  fit_options.candidates = options.candidates;
  fit_options.centers_per_round = options.centers_per_round;
  report.fit_tolerance = options.error_factor * bounding_box_diagonal(reference_n);
  fit_options.max_squared_error = report.fit_tolerance;
  fit_options.max_centers = options.max_centers;
  fit_options.blocked_update = options.blocked_update;
  // Time enters the field as (x, y, z, time_scale * t); velocities and the error bound follow, so
  // that eps still bounds |dx/dt - v|^2.
  const double time_scale = options.time_scale > 0.0 ? options.time_scale : automatic_time_scale(reference_n, target_n);
  report.time_scale = time_scale;
  Points4 scaled_positions = constraints.positions;
  scaled_positions.col(3) *= time_scale;
  fit_options.max_squared_error /= time_scale * time_scale;
  Eigen::MatrixX3d scaled_velocities = constraints.velocities / time_scale;
  const RbfFit fit(device, scaled_positions, scaled_velocities, fit_options);
  report.fit = fit.report();
  report.seconds.fitting = seconds_since(stage_start);
  stage("fitting", 1.0);

  stage_start = Clock::now();
  stage("integration", 0.0);
  Rk45Options integration_options = options.integration;
  integration_options.t_begin = 0.0;
  integration_options.t_end = time_scale;
  RbfField final_field = fit.field();
  const auto integrate = [&](const RbfField& field) {
    Eigen::MatrixX3d positions = reference_n;
    report.integration = summarize(device.integrate_rk45(*device.upload_field(field), positions, integration_options));
    return positions;
  };
  Eigen::MatrixX3d result_n = integrate(final_field);
  report.seconds.integration = seconds_since(stage_start);
  stage("integration", 1.0);

  stage_start = Clock::now();
  stage("drift compensation", 0.0);
  Eigen::MatrixX3d drift = endpoint_drift(result_n, target_n, constraints.vertices);
  std::vector<int> endpoint_index(static_cast<size_t>(reference.rows()), -1);
  for (std::size_t k = 0; k < constraints.vertices.size(); ++k) endpoint_index[static_cast<size_t>(constraints.vertices[k])] = static_cast<int>(k);
  report.drift.before = DriftSummary::of(drift);
  for (int pass = 0; pass < options.drift_passes; ++pass) {
    for (Eigen::Index row = 0; row < scaled_velocities.rows(); ++row) {
      const int k = endpoint_index[static_cast<size_t>(constraints.row_vertices[static_cast<size_t>(row)])];
      if (k >= 0) scaled_velocities.row(row) += drift.row(k) / time_scale;
    }
    final_field = fit.refit(scaled_velocities);
    result_n = integrate(final_field);
    drift = endpoint_drift(result_n, target_n, constraints.vertices);
  }
  report.drift.after = DriftSummary::of(drift);
  report.seconds.drift_compensation = seconds_since(stage_start);
  stage("drift compensation", 1.0);

  stage_start = Clock::now();
  const AdjacencyLists neighbours = vertex_neighbours(faces, static_cast<int>(reference.rows()));
  const detail::FaceTest new_faces = [&](const Eigen::MatrixX3d& pose) {
    return new_intersecting_faces(self_intersecting_faces(pose, faces), classification.reference_intersecting);
  };
  if (options.reproduction_rings >= 0) {
    // Faces the blend makes intersect are where it folds a corrected region onto the target's
    // shape, so the integrated result is kept around them too and the blend moves away.
    detail::ReproductionSettings settings;
    settings.keep_rings = options.reproduction_rings;
    settings.blend_rings = options.blend_rings;
    settings.attempts = kReproductionAttempts;
    detail::Reproduction reproduction = detail::reproduce_target(
        result_n, target_n, classification.near_intersections, faces, neighbours, settings, new_faces,
        new_faces(result_n));
    report.reproduction_skipped = !reproduction.pose;
    if (reproduction.pose) {
      result_n = std::move(*reproduction.pose);
      report.reproduced_vertices = reproduction.reproduced_vertices;
    }
  }
  report.seconds.reproduction = seconds_since(stage_start);

  stage_start = Clock::now();
  stage("verification", 0.0);
  if (options.fallback) {
    const detail::FallbackResult fallback = detail::restore_target_regions(
        result_n, target_n, classification.reference_intersecting, faces, classification.in_transit,
        kFallbackDeviation * bounding_box_diagonal(reference_n));
    report.fallback_vertices = fallback.vertices;
    report.fallback_regions = fallback.regions;
    report.fallback_global_regions = fallback.global_regions;
    report.fallback_smoothed_regions = fallback.smoothed_regions;
    report.integrated_new_intersecting_faces = fallback.new_faces_before;
    if (fallback.regions > 0 || fallback.smoothed_regions > 0 || fallback.rejected_regions > 0) {
      report.fallback_note = std::to_string(fallback.new_faces_before) + " new intersecting faces after integration; " +
                             std::to_string(fallback.regions) + " region(s) (" + std::to_string(fallback.vertices) +
                             " vertices) taken from the target, " + std::to_string(fallback.global_regions) +
                             " of them where the key frames move a part through another; " +
                             std::to_string(fallback.smoothed_regions) + " small region(s) smoothed; " +
                             std::to_string(fallback.rejected_regions) + " region(s) left as integrated";
    }
  }
  report.seconds.verification = seconds_since(stage_start);

  std::unique_ptr<DeviceField> uploaded;
  const detail::PathSampler paths = [&](const std::vector<int>& vertices, int segments) {
    if (!uploaded) uploaded = device.upload_field(final_field);
    Eigen::MatrixX3d positions(static_cast<Eigen::Index>(vertices.size()), 3);
    for (size_t i = 0; i < vertices.size(); ++i) positions.row(static_cast<Eigen::Index>(i)) = reference_n.row(vertices[i]);
    std::vector<Eigen::MatrixX3d> samples{positions};
    Rk45Options segment = integration_options;
    for (int k = 1; k <= segments; ++k) {
      segment.t_begin = time_scale * (k - 1) / segments;
      segment.t_end = time_scale * k / segments;
      device.integrate_rk45(*uploaded, positions, segment);
      samples.push_back(positions);
    }
    return samples;
  };
  // What the last stages did to one candidate pose.
  struct Mending {
    Eigen::MatrixX3d pose;
    bool rolled_back = false;
    int rollback_new_faces_before = 0, rollback_regions = 0, rollback_vertices = 0;
    double rollback_earliest_time = 1.0;
    detail::LocalCorrectionResult local;
    detail::RelaxationResult relaxation;
    bool from_target = false;
    bool through_halfway = false;
    int new_faces = 0;
  };
  const auto roll_back = [&](Mending& m) {
    const Clock::time_point begin = Clock::now();
    stage("rollback", 0.0);
    const detail::RollbackResult rollback =
        detail::roll_back_regions(m.pose, paths, faces, classification.reference_intersecting);
    if (!m.rolled_back) m.rollback_new_faces_before = rollback.new_faces_before;
    m.rolled_back = true;
    m.rollback_regions += rollback.regions;
    m.rollback_vertices += rollback.vertices;
    m.rollback_earliest_time = std::min(m.rollback_earliest_time, rollback.earliest_time);
    m.new_faces = rollback.new_faces_after;
    report.seconds.rollback += seconds_since(begin);
    stage("rollback", 1.0);
  };
  const auto correct_locally = [&](Mending& m) {
    const Clock::time_point begin = Clock::now();
    stage("local correction", 0.0);
    const detail::LocalCorrectionResult local = detail::correct_regions_locally(
        m.pose, reference_n, faces, classification.reference_intersecting, device, options);
    if (m.local.new_faces_before == 0) m.local.new_faces_before = local.new_faces_before;
    m.local.new_faces_after = local.new_faces_after;
    m.local.regions += local.regions;
    m.local.vertices += local.vertices;
    m.new_faces = local.new_faces_after;
    report.seconds.local_correction += seconds_since(begin);
    stage("local correction", 1.0);
  };
  const auto relax = [&](Mending& m) {
    if (!options.relaxation || m.new_faces == 0) return;
    const Clock::time_point begin = Clock::now();
    stage("relaxation", 0.0);
    m.relaxation = detail::relax_folded_regions(m.pose, reference_n, faces, classification.reference_intersecting);
    m.new_faces = m.relaxation.new_faces_after;
    report.seconds.relaxation += seconds_since(begin);
    stage("relaxation", 1.0);
  };
  const auto median_distance = [&](const Mending& m) { return DriftSummary::of(m.pose - target_n).median; };
  // Fewer new faces first; between equals, the one nearer the target.
  const auto better = [&](const Mending& a, const Mending& b) {
    return a.new_faces != b.new_faces ? a.new_faces < b.new_faces : median_distance(a) < median_distance(b);
  };
  // Rollback first, as it changes least; what it cannot free is corrected again region by region,
  // and what that leaves is rolled back once more. Either stage can spoil the other's chances (a
  // rollback can leave a region no local correction frees, and the other way round), so where
  // faces remain the other order is tried too, from the same pose, and the better result kept.
  Mending mended;
  mended.pose = result_n;
  // The relaxation needs the count the other stages would have given it.
  if (!options.rollback && !options.local_correction) mended.new_faces = static_cast<int>(new_faces(result_n).size());
  if (options.rollback) roll_back(mended);
  if (options.local_correction && (!mended.rolled_back || mended.new_faces > 0)) {
    correct_locally(mended);
    if (options.rollback && mended.local.regions > 0) roll_back(mended);
  }
  relax(mended);
  if (options.rollback && options.local_correction && mended.new_faces > 0) {
    Mending other;
    other.pose = result_n;
    correct_locally(other);
    if (other.new_faces > 0) roll_back(other);
    relax(other);
    if (better(other, mended)) mended = std::move(other);
  }
  // Where the target is entangled over much of the pose, the field leaves most of it off the
  // target; correcting only the target's own entangled regions, each on its own, can then free
  // the pose and stay nearer the target (lion-04).
  if (options.local_correction && mended.new_faces > 0) {
    Mending from_target;
    from_target.pose = target_n;
    from_target.from_target = true;
    correct_locally(from_target);
    if (options.rollback && from_target.new_faces > 0) roll_back(from_target);
    relax(from_target);
    if (better(from_target, mended)) mended = std::move(from_target);
  }
  // Where faces still remain, the correction is tried in two legs through the pose halfway in edge
  // space (edge lengths and dihedral angles interpolated), each leg with its own key frames and
  // field: on the most entangled shared poses that freed what the whole way could not (lion-07: 154
  // new faces the whole way, 0 in two legs; the middle Poisson key frame as the halfway pose: 229).
  if (options.intermediate_pose && mended.new_faces > 0) {
    const Clock::time_point begin = Clock::now();
    stage("halfway pose", 0.0);
    try {
      PoseSet ends(faces);
      ends.add_pose(reference_n);
      ends.add_pose(target_n);
      InterpolationOptions edge_space;
      edge_space.method = InterpolationMethod::edge;
      const Eigen::MatrixX3d halfway = interpolate_poses(ends, two_pose_weights(0.5), edge_space);
      CorrectionOptions leg = options;
      leg.intermediate_pose = false;
      // The whole pose's separation runs after the legs, from the target itself; inside a leg it
      // traded the leg's own field for less (lion-07: 4.2e-4 of the diagonal off the target with
      // it, 2.4e-5 without).
      leg.contact_separation = false;
      leg.excluded_vertices.clear();
      CorrectionReport first_leg;
      const Eigen::MatrixX3d halfway_corrected = correct_pose(reference_n, halfway, faces, device, leg, &first_leg);
      Mending two_legs;
      two_legs.pose = correct_pose(halfway_corrected, target_n, faces, device, leg);
      two_legs.through_halfway = true;
      two_legs.new_faces = static_cast<int>(new_faces(two_legs.pose).size());
      report.halfway_new_faces = first_leg.new_intersecting_faces;
      report.halfway_tried = true;
      if (better(two_legs, mended)) mended = std::move(two_legs);
    } catch (const DeviceError&) {
      throw;
    } catch (const Error&) {
      // No halfway pose for this mesh (edge space needs a manifold surface): the one-leg result stands.
    }
    report.seconds.halfway = seconds_since(begin);
    stage("halfway pose", 1.0);
  }
  result_n = std::move(mended.pose);
  report.through_halfway = mended.through_halfway;
  // The stages since the first reproduction keep or move whole regions; now only the target's own
  // intersections and what is still new need the corrected positions, and the rest of the pose can
  // be the target again wherever that adds no intersection.
  if (options.reproduction_rings >= 0) {
    const Clock::time_point begin = Clock::now();
    std::vector<char> kept(static_cast<size_t>(reference.rows()), 0);
    const std::vector<int> remaining = new_faces(result_n);
    const std::vector<int> target_new =
        new_intersecting_faces(classification.target_intersecting, classification.reference_intersecting);
    for (const std::vector<int>* face_list : {&target_new, &remaining}) {
      for (int f : *face_list) {
        for (int c = 0; c < 3; ++c) kept[static_cast<size_t>(faces(f, c))] = 1;
      }
    }
    detail::ReproductionSettings settings;
    settings.blend_rings = options.blend_rings;
    settings.widening_rings = 1;
    settings.attempts = kFinalReproductionAttempts;
    detail::Reproduction reproduction =
        detail::reproduce_target(result_n, target_n, kept, faces, neighbours, settings, new_faces, remaining);
    if (reproduction.pose) {
      result_n = std::move(*reproduction.pose);
      report.final_reproduced_vertices = reproduction.reproduced_vertices;
    }
    report.seconds.reproduction += seconds_since(begin);
  }
  // The field moves whole parts; where that left new faces or moved most of the pose off the
  // target (cat-07, curled up with its head sunk into its paws: 0 new faces, but more than half of
  // the vertices over 1e-2 of the diagonal away), the target's own contacts are separated instead.
  if (options.contact_separation && options.reproduction_rings >= 0) {
    const double median = DriftSummary::of(result_n - target_n).median;
    const std::vector<int> remaining = new_faces(result_n);
    if (!remaining.empty() || median > options.separation_tolerance * bounding_box_diagonal(reference_n)) {
      const Clock::time_point begin = Clock::now();
      stage("contact separation", 0.0);
      detail::SeparationResult separation =
          detail::separate_contacts(target_n, reference_n, faces, classification.reference_intersecting);
      report.separation_tried = true;
      report.separation_new_faces = separation.new_faces_after;
      report.separation_rounds = separation.iterations;
      const auto remaining_count = static_cast<int>(remaining.size());
      if (separation.new_faces_after < remaining_count ||
          (separation.new_faces_after == remaining_count &&
           DriftSummary::of(separation.pose - target_n).median < median)) {
        result_n = std::move(separation.pose);
        report.separated = true;
      }
      report.seconds.separation = seconds_since(begin);
      stage("contact separation", 1.0);
    }
  }
  report.rollback_new_faces_before = mended.rollback_new_faces_before;
  report.rollback_regions = mended.rollback_regions;
  report.rollback_vertices = mended.rollback_vertices;
  report.rollback_earliest_time = mended.rollback_earliest_time;
  report.local_new_faces_before = mended.local.new_faces_before;
  report.local_regions = mended.local.regions;
  report.local_vertices = mended.local.vertices;
  report.local_from_target = mended.from_target;
  report.relaxation_new_faces_before = mended.relaxation.new_faces_before;
  report.relaxation_regions = mended.relaxation.regions;
  report.relaxation_vertices = mended.relaxation.vertices;

  stage_start = Clock::now();
  Eigen::MatrixX3d result = normalization.undo(result_n);
  // Vertices that are the target's own get its coordinates exactly, not their normalization's round trip.
  for (Eigen::Index v = 0; v < result.rows(); ++v) {
    if (result_n.row(v) == target_n.row(v)) result.row(v) = target.row(v);
  }
  const std::vector<int> result_intersecting = self_intersecting_faces(result, faces);
  report.result_intersecting_faces = static_cast<int>(result_intersecting.size());
  report.new_intersecting_faces = static_cast<int>(
      new_intersecting_faces(result_intersecting, classification.reference_intersecting).size());
  const Eigen::MatrixX3d difference = result - target;
  const DriftSummary distance_to_target = DriftSummary::of(difference);
  report.max_distance_to_target = distance_to_target.max;
  report.median_distance_to_target = distance_to_target.median;
  // The same over the vertices near intersections alone: how far the correction moved them.
  std::vector<Eigen::Index> near_rows;
  for (size_t v = 0; v < classification.near_intersections.size(); ++v) {
    if (classification.near_intersections[v]) near_rows.push_back(static_cast<Eigen::Index>(v));
  }
  report.near_intersection_vertices = static_cast<int>(near_rows.size());
  report.median_distance_near_intersections = DriftSummary::of(difference(near_rows, Eigen::all)).median;
  const Eigen::VectorXd stretch =
      edge_stretch(result, reference, target, faces, kShortestStretchedEdge * edge_lengths(reference, edge_map(faces).edges).mean());
  report.stretched_faces = static_cast<int>((stretch.array() > kStretchedFactor).count());
  report.largest_stretch = stretch.maxCoeff();
  report.seconds.verification += seconds_since(stage_start);
  stage("verification", 1.0);

  report.seconds.total = seconds_since(start);
  if (report_out != nullptr) *report_out = std::move(report);
  return result;
}

}  // namespace posekit
