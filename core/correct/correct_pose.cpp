// The correction: checks, the unit-sphere frame, the repair ladder on the target, and the
// measurements of the result against the reference and the target.
#include "correct/fixed_product_blocking.hpp"
#include "correct/nested_correction.hpp"
#include "correct/repair_ladder.hpp"

#include <posekit/correct.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace posekit {
namespace detail {
namespace {

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
  require(options.collar_rings >= 1, "collar_rings must be >= 1, got " + std::to_string(options.collar_rings));
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
  check_disabled_stages(options.disabled_stages);
  validate_rk45_step_control(options.integration);
}

void check_pose(const Eigen::Ref<const Eigen::MatrixX3d>& pose, const char* name) {
  if (pose.rows() == 0) throw ArgumentError(std::string(name) + " has no vertices");
  for (Eigen::Index v = 0; v < pose.rows(); ++v) {
    if (!pose.row(v).allFinite()) {
      throw ArgumentError(std::string(name) + " vertex " + std::to_string(v) + " has a coordinate that is not finite");
    }
  }
}

ResultReport measure_result(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                            const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                            const Eigen::Ref<const Eigen::MatrixX3d>& target,
                            const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                            const CorrectionContext& context) {
  ResultReport out;
  out.bounding_box_diagonal = bounding_box_diagonal(reference);
  out.reference_intersecting_faces = static_cast<int>(context.reference_intersecting.size());
  out.target_intersecting_faces = static_cast<int>(faces_in_pairs(context.target_pairs).size());
  const std::vector<int> intersecting = self_intersecting_faces(result, faces);
  out.intersecting_faces = static_cast<int>(intersecting.size());
  out.new_intersecting_faces =
      static_cast<int>(new_intersecting_faces(intersecting, context.reference_intersecting).size());
  const Eigen::MatrixX3d difference = result - target;
  const DriftSummary distance = DriftSummary::of(difference);
  out.median_distance_to_target = distance.median;
  out.max_distance_to_target = distance.max;
  out.changed_vertices = static_cast<int>((difference.rowwise().squaredNorm().array() > 0.0).count());
  // The same over the vertices near intersections alone: how far the correction moved them.
  std::vector<Eigen::Index> near_rows;
  if (context.pair_analysis->classification) {
    const std::vector<char>& near = context.pair_analysis->classification->near_intersections;
    for (size_t v = 0; v < near.size(); ++v) {
      if (near[v]) near_rows.push_back(static_cast<Eigen::Index>(v));
    }
  }
  out.near_intersection_vertices = static_cast<int>(near_rows.size());
  out.median_distance_near_intersections = DriftSummary::of(difference(near_rows, Eigen::all)).median;
  const Eigen::VectorXd stretch = StretchMeasure(reference, target, faces).per_face(result);
  out.stretched_faces = static_cast<int>((stretch.array() > kStretchedFactor).count());
  out.strongly_stretched_faces = static_cast<int>((stretch.array() > kStronglyStretchedFactor).count());
  out.largest_stretch = stretch.size() > 0 ? stretch.maxCoeff() : 0.0;
  return out;
}

}  // namespace

CorrectionContext make_context(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                               const Eigen::Ref<const Eigen::MatrixX3d>& target,
                               const Eigen::Ref<const Eigen::MatrixX3i>& faces, Device& device,
                               const CorrectionOptions& options,
                               CorrectionScope scope, const CorrectionProgress& progress,
                               std::shared_ptr<PairAnalysis> same_pair) {
  CorrectionContext context{reference, target,  faces, device, options, scope, {}, {}, {}, {}, 0,
                            0.0,       StretchMeasure(reference, target, faces), progress, nullptr, {}};
  context.neighbours = vertex_neighbours(faces, static_cast<int>(reference.rows()));
  if (same_pair && !same_pair->tested_pairs.empty()) {
    context.reference_pairs = same_pair->tested_pairs.front();
    context.target_pairs = same_pair->tested_pairs.back();
  } else {
    context.reference_pairs = self_intersecting_face_pairs(reference, faces);
    context.target_pairs = self_intersecting_face_pairs(target, faces);
  }
  if (same_pair) context.pair_analysis = std::move(same_pair);
  context.reference_intersecting = faces_in_pairs(context.reference_pairs);
  context.target_new_faces = static_cast<int>(
      new_intersecting_faces(faces_in_pairs(context.target_pairs), context.reference_intersecting).size());
  context.diagonal = bounding_box_diagonal(reference);
  return context;
}

Eigen::MatrixX3d correct_in_scope(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& target,
                                  const Eigen::Ref<const Eigen::MatrixX3i>& faces, Device& device,
                                  const CorrectionOptions& options,
                                  CorrectionScope scope, CorrectionReport* report_out,
                                  const CorrectionProgress& progress, const std::vector<int>* allowed,
                                  LentAnalysis same_pair) {
  const auto start = std::chrono::steady_clock::now();
  const FixedProductBlocking fixed_blocking;
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

  const auto normalization_start = std::chrono::steady_clock::now();
  // A pair lent in its analysis's frame stays there: the identity keeps it.
  const UnitSphereNormalization normalization = same_pair.analysis && same_pair.poses_in_its_frame
                                                    ? UnitSphereNormalization{}
                                                    : shared_unit_sphere_normalization({reference, target});
  const Eigen::MatrixX3d reference_n = normalization.apply(reference);
  const Eigen::MatrixX3d target_n = normalization.apply(target);
  // Nested runs name no vertex of the whole pose.
  CorrectionOptions scoped = options;
  if (scope != CorrectionScope::whole_pose && scope != CorrectionScope::stretch_retry) scoped.excluded_vertices.clear();
  CorrectionContext context =
      make_context(reference_n, target_n, faces, device, scoped, scope, progress, std::move(same_pair.analysis));
  if (allowed != nullptr) {
    context.reference_intersecting = *allowed;
    context.target_new_faces = static_cast<int>(
        new_intersecting_faces(faces_in_pairs(context.target_pairs), context.reference_intersecting).size());
  }
  context.field_report = &report.field;
  report.field.seconds.normalization =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - normalization_start).count();

  Candidate start_candidate(target_n, faces, context.reference_intersecting, context.target_pairs);
  const Candidate corrected = run_repair_ladder(default_repair_ladder(), std::move(start_candidate), context, report.stages);

  Eigen::MatrixX3d result = normalization.undo(corrected.pose());
  // Vertices that are the target's own get its coordinates exactly, not their normalization's round trip.
  for (Eigen::Index v = 0; v < result.rows(); ++v) {
    if (corrected.pose().row(v) == target_n.row(v)) result.row(v) = target.row(v);
  }
  if (report_out != nullptr) {
    report.result = measure_result(result, reference, target, faces, context);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    *report_out = std::move(report);
  }
  return result;
}

}  // namespace detail

DriftSummary DriftSummary::of(const Eigen::Ref<const Eigen::MatrixX3d>& differences) {
  DriftSummary summary;
  if (differences.rows() == 0) return summary;
  Eigen::VectorXd distances = differences.rowwise().norm();
  summary.max = distances.maxCoeff();
  const auto middle = distances.data() + distances.size() / 2;
  std::nth_element(distances.data(), middle, distances.data() + distances.size());
  summary.median = *middle;
  return summary;
}

int FieldReport::constraints() const {
  int sum = 0;
  for (const FieldRegionReport& region : regions) sum += region.constraints;
  return sum;
}

int FieldReport::centers() const {
  int sum = 0;
  for (const FieldRegionReport& region : regions) sum += region.fit.centers;
  return sum;
}

bool FieldReport::converged() const {
  return std::all_of(regions.begin(), regions.end(),
                     [](const FieldRegionReport& region) { return region.constraints == 0 || region.fit.converged; });
}

const StageReport* CorrectionReport::stage(const std::string& name) const {
  for (auto it = stages.rbegin(); it != stages.rend(); ++it) {
    if (it->name == name) return &*it;
  }
  return nullptr;
}

Eigen::MatrixX3d correct_pose(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                              const Eigen::Ref<const Eigen::MatrixX3d>& target,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                              Device& device, const CorrectionOptions& options, CorrectionReport* report,
                              const CorrectionProgress& progress) {
  return detail::correct_in_scope(reference, target, faces, device, options, detail::CorrectionScope::whole_pose,
                                  report, progress);
}

}  // namespace posekit
