// The correction pipeline: normalize, key frames, classification, constraints, field fitting,
// integration, verification and the fallback for global intersections.
#include <posekit/correct.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/poisson_interpolation.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include "correct/global_intersection_fallback.hpp"
#include "correct/vertex_classification.hpp"
#include "correct/vertex_trajectories.hpp"

#include <algorithm>
#include <chrono>
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
  require(options.constraint_times >= 2,
          "constraint_times must be >= 2, got " + std::to_string(options.constraint_times));
  require(options.exclusion_rings >= 0,
          "exclusion_rings must be >= 0, got " + std::to_string(options.exclusion_rings));
  require(std::isfinite(options.error_factor) && options.error_factor > 0.0,
          "error_factor must be finite and > 0, got " + std::to_string(options.error_factor));
  validate_rk45_options(options.integration);
}

void check_pose(const Eigen::MatrixX3d& pose, const char* name) {
  if (pose.rows() == 0) throw ArgumentError(std::string(name) + " has no vertices");
  for (Eigen::Index v = 0; v < pose.rows(); ++v) {
    if (!pose.row(v).allFinite()) {
      throw ArgumentError(std::string(name) + " vertex " + std::to_string(v) + " has a coordinate that is not finite");
    }
  }
}

}  // namespace

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
  const detail::VertexClassification classification =
      detail::classify_vertices(frames, faces, options.exclusion_rings, options.excluded_vertices);
  report.excluded_vertices = classification.excluded;
  report.reference_intersecting_faces = static_cast<int>(classification.reference_intersecting.size());
  report.target_intersecting_faces = static_cast<int>(classification.target_intersecting.size());
  report.seconds.classification = seconds_since(stage_start);
  stage("classification", 1.0);

  stage_start = Clock::now();
  const detail::VertexTrajectories trajectories(std::move(frames));
  const detail::SpaceTimeConstraints constraints =
      detail::sample_constraints(trajectories, classification.constrained, options.constraint_times);
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
  const RbfField field = fit_rbf_field(device, constraints.positions, constraints.velocities, fit_options, &report.fit);
  report.seconds.fitting = seconds_since(stage_start);
  stage("fitting", 1.0);

  stage_start = Clock::now();
  stage("integration", 0.0);
  Eigen::MatrixX3d result_n = reference_n;
  const std::unique_ptr<DeviceField> device_field = device.upload_field(field);
  report.integration = summarize(device.integrate_rk45(*device_field, result_n, options.integration));
  report.seconds.integration = seconds_since(stage_start);
  stage("integration", 1.0);

  stage_start = Clock::now();
  stage("verification", 0.0);
  if (options.fallback) {
    const detail::FallbackResult fallback = detail::restore_unreachable_regions(
        result_n, target_n, classification.reference_intersecting, faces, classification.in_transit,
        kFallbackDeviation * bounding_box_diagonal(reference_n));
    report.fallback_vertices = fallback.vertices;
    if (fallback.regions > 0 || fallback.rejected_regions > 0) {
      report.fallback_note = "key frames move a part through another part; " + std::to_string(fallback.regions) +
                             " such region(s) (" + std::to_string(fallback.vertices) +
                             " vertices) taken from the target, " + std::to_string(fallback.rejected_regions) +
                             " left as integrated because the target's region would intersect";
    }
  }
  Eigen::MatrixX3d result = normalization.undo(result_n);
  const std::vector<int> result_intersecting = self_intersecting_faces(result, faces);
  report.result_intersecting_faces = static_cast<int>(result_intersecting.size());
  report.new_intersecting_faces = static_cast<int>(
      new_intersecting_faces(result_intersecting, classification.reference_intersecting).size());
  Eigen::VectorXd distances = (result - target).rowwise().norm();
  report.max_distance_to_target = distances.maxCoeff();
  const auto middle = distances.data() + distances.size() / 2;
  std::nth_element(distances.data(), middle, distances.data() + distances.size());
  report.median_distance_to_target = *middle;
  report.seconds.verification = seconds_since(stage_start);
  stage("verification", 1.0);

  report.seconds.total = seconds_since(start);
  if (report_out != nullptr) *report_out = std::move(report);
  return result;
}

}  // namespace posekit
