// The field correction, the first stage of the ladder: key frames from the reference to the
// target in gradient space, the vertices whose trajectories constrain the field, the regions of
// interest, one space-time field fitted to each region's trajectories, the reference's vertices
// integrated through it with drift compensation, and reproduction of the target away from what
// needed correcting.
#include "correct/regions_of_interest.hpp"
#include "correct/repair_stage.hpp"
#include "correct/target_reproduction.hpp"
#include "correct/vertex_classification.hpp"
#include "correct/vertex_trajectories.hpp"

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/poisson_interpolation.hpp>
#include <posekit/rbf_fitting.hpp>
#include <posekit/self_intersections.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>

namespace posekit::detail {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Bounds of the automatic time scale: trajectories that hardly move still need time to count, and
// beyond the authors' equal weighting the fits measured no better.
constexpr double kSmallestTimeScale = 0.05;
constexpr double kLargestTimeScale = 1.0;

// Rounds in which reproduction widens what it keeps of the integrated result before it gives up.
constexpr int kReproductionAttempts = 4;

// The greedy fit needs at least this many constraints (two rounds' worth of a quadratic in R^4).
constexpr Eigen::Index kFewestConstraints = 20;

// The root mean square distance a vertex of the region travels from the reference to the target
// (unit-sphere frame): with time weighted so, a typical trajectory climbs about as much in time as
// it moves in space. docs/correct.md has the measurements behind it.
double automatic_time_scale(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                            const Eigen::Ref<const Eigen::MatrixX3d>& target,
                            const std::vector<int>& vertices) {
  double sum = 0.0;
  for (int v : vertices) sum += (target.row(v) - reference.row(v)).squaredNorm();
  const double rms = vertices.empty() ? kLargestTimeScale : std::sqrt(sum / static_cast<double>(vertices.size()));
  return std::clamp(std::isfinite(rms) ? rms : kLargestTimeScale, kSmallestTimeScale, kLargestTimeScale);
}

// The poses tested for intersections: the key frames and, between each two, `substeps` - 1 poses
// of the trajectories. Between key frames an intersection sweeps a band over the surface that the
// frames alone miss, where a part passing through another would find the other's constraints and
// be dragged along.
std::vector<Eigen::MatrixX3d> tested_poses(const std::vector<Eigen::MatrixX3d>& frames,
                                           const VertexTrajectories& trajectories, int substeps) {
  std::vector<Eigen::MatrixX3d> poses;
  const int intervals = static_cast<int>(frames.size()) - 1;
  for (int i = 0; i <= intervals * substeps; ++i) {
    poses.push_back(i % substeps == 0 ? frames[static_cast<size_t>(i / substeps)]
                                      : trajectories.pose(static_cast<double>(i) / (intervals * substeps)));
  }
  return poses;
}

// Each tested pose's intersecting pairs; the two ends are known already. The poses are tested side
// by side, each test's own parallel search inside.
std::vector<FacePairs> intersecting_pairs(const std::vector<Eigen::MatrixX3d>& poses,
                                          const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                          const FacePairs& first, const FacePairs& last) {
  std::vector<FacePairs> pairs(poses.size());
  pairs.front() = first;
  pairs.back() = last;
  tbb::parallel_for(size_t{1}, poses.size() - 1, [&](size_t i) { pairs[i] = self_intersecting_face_pairs(poses[i], faces); });
  return pairs;
}

// Which vertices of `region` constrain the field at each constraint time: those constrained
// throughout, or, with an exclusion window, all but those near an intersection of a tested pose
// within the window (in key-frame spacings) of that time.
std::vector<std::vector<char>> constrained_at_times(const VertexClassification& classification,
                                                    const std::vector<int>& region, const CorrectionOptions& options) {
  const auto time_count = static_cast<size_t>(options.constraint_times);
  const auto vertex_count = classification.constrained.size();
  std::vector<std::vector<char>> constrained(time_count, std::vector<char>(vertex_count, 0));
  const double window = options.exclusion_window;
  const auto pose_count = static_cast<int>(classification.unconstrained_in_frame.size());
  for (size_t step = 0; step < time_count; ++step) {
    std::vector<char>& flags = constrained[step];
    for (int v : region) flags[static_cast<size_t>(v)] = window < 0 ? classification.constrained[static_cast<size_t>(v)] : 1;
    if (window < 0) continue;
    const double pose_time = static_cast<double>(step) / static_cast<double>(time_count - 1) * (pose_count - 1);
    for (int pose = 0; pose < pose_count; ++pose) {
      if (std::abs(pose - pose_time) > window * options.intersection_substeps) continue;
      const std::vector<char>& excluded = classification.unconstrained_in_frame[static_cast<size_t>(pose)];
      for (int v : region) {
        if (excluded[static_cast<size_t>(v)]) flags[static_cast<size_t>(v)] = 0;
      }
    }
  }
  return constrained;
}

// One region's field and where it took the region's vertices.
struct RegionField {
  FieldRegionReport report;
  TimedField field;
  Eigen::MatrixX3d end_positions;  // rows in the order of the region's vertices
  bool fitted = false;             // too few constraints: the region keeps the target
  double fitting_seconds = 0, integration_seconds = 0, drift_seconds = 0;
};

RegionField fit_region(const std::vector<int>& region, const VertexClassification& classification,
                       const VertexTrajectories& trajectories, const CorrectionContext& context, double tolerance) {
  const CorrectionOptions& options = context.options;
  RegionField out;
  out.report.vertices = static_cast<int>(region.size());
  for (int v : region) out.report.unconstrained_vertices += classification.constrained[static_cast<size_t>(v)] ? 0 : 1;
  const SpaceTimeConstraints constraints =
      sample_constraints(trajectories, constrained_at_times(classification, region, options));
  out.report.constraints = static_cast<int>(constraints.positions.rows());
  out.end_positions = context.target(region, Eigen::all);
  if (constraints.positions.rows() < kFewestConstraints) return out;

  Clock::time_point start = Clock::now();
  const double time_scale =
      options.time_scale > 0.0 ? options.time_scale : automatic_time_scale(context.reference, context.target, region);
  out.report.time_scale = time_scale;
  // Time enters the field as (x, y, z, time_scale * t); velocities and the error bound follow, so
  // that eps still bounds |dx/dt - v|^2.
  RbfFitOptions fit_options;
  fit_options.candidates = options.candidates;
  fit_options.centers_per_round = options.centers_per_round;
  fit_options.max_squared_error = tolerance / (time_scale * time_scale);
  fit_options.max_centers = options.max_centers;
  fit_options.blocked_update = options.blocked_update;
  Points4 scaled_positions = constraints.positions;
  scaled_positions.col(3) *= time_scale;
  Eigen::MatrixX3d scaled_velocities = constraints.velocities / time_scale;
  const RbfFit fit(context.device, scaled_positions, scaled_velocities, fit_options);
  out.report.fit = fit.report();
  out.fitting_seconds = seconds_since(start);

  // Each pass but the last needs only the ends of the vertices whose drift it measures (those
  // constrained at the end), so only those are integrated; the last integrates the whole region.
  // Particles are integrated independently, so their ends are the same either way.
  start = Clock::now();
  const Rk45Options integration{options.integration, 0.0, time_scale};
  out.field = {fit.field(), time_scale};
  const auto integrate = [&](const RbfField& field, const std::vector<int>& vertices) {
    Eigen::MatrixX3d positions = context.reference(vertices, Eigen::all);
    out.report.integration =
        summarize(context.device.integrate_rk45(*context.device.upload_field(field), positions, integration));
    return positions;
  };
  const auto last_pass = [&](int pass) { return pass == options.drift_passes; };
  const auto integrate_for_pass = [&](int pass) {
    return integrate(out.field.field, last_pass(pass) ? region : constraints.vertices);
  };
  Eigen::MatrixX3d ends = integrate_for_pass(0);
  out.integration_seconds = seconds_since(start);

  // Endpoint drift of the vertices constrained at the end: before the last pass the ends are theirs
  // alone, in the last they are the region's, read at those vertices' rows.
  start = Clock::now();
  std::vector<int> region_row(classification.constrained.size(), -1);
  for (size_t i = 0; i < region.size(); ++i) region_row[static_cast<size_t>(region[i])] = static_cast<int>(i);
  std::vector<int> constrained_rows;
  constrained_rows.reserve(constraints.vertices.size());
  for (int v : constraints.vertices) constrained_rows.push_back(region_row[static_cast<size_t>(v)]);
  const Eigen::MatrixX3d goal = context.target(constraints.vertices, Eigen::all);
  const auto drift_of = [&](const Eigen::MatrixX3d& pass_ends, int pass) -> Eigen::MatrixX3d {
    if (last_pass(pass)) return goal - pass_ends(constrained_rows, Eigen::all);
    return goal - pass_ends;
  };
  std::vector<int> drift_row(classification.constrained.size(), -1);
  for (size_t k = 0; k < constraints.vertices.size(); ++k) drift_row[static_cast<size_t>(constraints.vertices[k])] = static_cast<int>(k);
  Eigen::MatrixX3d drift = drift_of(ends, 0);
  out.report.drift.before = DriftSummary::of(drift);
  for (int pass = 0; pass < options.drift_passes; ++pass) {
    for (Eigen::Index row = 0; row < scaled_velocities.rows(); ++row) {
      const int k = drift_row[static_cast<size_t>(constraints.row_vertices[static_cast<size_t>(row)])];
      if (k >= 0) scaled_velocities.row(row) += drift.row(k) / time_scale;
    }
    out.field.field = fit.refit(scaled_velocities);
    ends = integrate_for_pass(pass + 1);
    drift = drift_of(ends, pass + 1);
  }
  out.end_positions = std::move(ends);
  out.report.drift.after = DriftSummary::of(drift);
  out.drift_seconds = seconds_since(start);
  out.fitted = true;
  return out;
}

// The key frames, the pairs that intersect in the tested poses and the classification, into the
// context's pair analysis, with their seconds in `report`.
void analyze_pair(const CorrectionContext& context, FieldReport& report) {
  const CorrectionOptions& options = context.options;
  PairAnalysis& analysis = *context.pair_analysis;
  Clock::time_point start = Clock::now();
  context.report_progress("key frames", 0.0);
  std::vector<Eigen::MatrixX3d> frames =
      PoissonInterpolator(context.reference, context.target, context.faces).key_frames(options.key_frames);
  frames.front() = context.reference;  // exact ends, not the solver's round-off
  frames.back() = context.target;
  report.seconds.key_frames = seconds_since(start);

  start = Clock::now();
  context.report_progress("classification", 0.0);
  analysis.trajectories = std::make_shared<const VertexTrajectories>(std::move(frames));
  const std::vector<Eigen::MatrixX3d> poses =
      tested_poses(analysis.trajectories->frames(), *analysis.trajectories, options.intersection_substeps);
  analysis.tested_pairs = intersecting_pairs(poses, context.faces, context.reference_pairs, context.target_pairs);
  analysis.classification = classify_vertices(analysis.tested_pairs, context.faces, context.neighbours,
                                              options.exclusion_rings, options.excluded_vertices);
  report.seconds.classification = seconds_since(start);
}

class FieldStage final : public RepairStage {
 public:
  FieldStage()
      : RepairStage({"field", "fit a space-time field to the trajectories near what intersects and integrate the reference through it",
                     false},
                    kEveryScope) {}

  bool wanted(const Candidate& /*current*/, const CorrectionContext& /*context*/) const override { return true; }

  std::optional<Candidate> run(const Candidate& current, CorrectionContext& context, StageReport& stage) override {
    const CorrectionOptions& options = context.options;
    FieldReport& report = *context.field_report;
    report.whole_mesh = options.whole_mesh;
    report.collar_rings = options.whole_mesh ? 0 : options.collar_rings;
    report.key_frames = options.key_frames;

    PairAnalysis& analysis = *context.pair_analysis;
    if (!analysis.classification) analyze_pair(context, report);
    const VertexClassification& classification = *analysis.classification;
    const std::vector<FacePairs>& pairs = analysis.tested_pairs;
    const std::shared_ptr<const VertexTrajectories>& trajectories = analysis.trajectories;
    report.tested_poses = static_cast<int>(pairs.size());
    report.excluded_vertices = classification.excluded;
    report.reference_intersecting_faces = static_cast<int>(classification.reference_intersecting.size());
    report.target_intersecting_faces = static_cast<int>(classification.target_intersecting.size());
    report.near_intersection_vertices = static_cast<int>(
        std::count(classification.near_intersections.begin(), classification.near_intersections.end(), 1));

    Clock::time_point start = Clock::now();
    const std::vector<std::vector<int>> regions =
        options.whole_mesh ? whole_mesh_region(context.vertex_count())
                           : regions_of_interest(classification, pairs, context.faces, context.neighbours,
                                                 options.collar_rings);
    for (const std::vector<int>& region : regions) report.region_vertices += static_cast<int>(region.size());
    report.seconds.regions = seconds_since(start);

    context.report_progress("fitting", 0.0);
    report.fit_tolerance = options.error_factor * context.diagonal;
    std::vector<RegionField> fields(regions.size());
    tbb::parallel_for(size_t{0}, regions.size(), [&](size_t r) {
      fields[r] = fit_region(regions[r], classification, *trajectories, context, report.fit_tolerance);
    });
    Eigen::MatrixX3d integrated = context.target;
    std::vector<TimedField> timed;
    std::vector<int> field_of_vertex(static_cast<size_t>(context.vertex_count()), -1);
    for (size_t r = 0; r < regions.size(); ++r) {
      RegionField& field = fields[r];
      report.seconds.fitting += field.fitting_seconds;
      report.seconds.integration += field.integration_seconds;
      report.seconds.drift_compensation += field.drift_seconds;
      report.regions.push_back(field.report);
      if (!field.fitted) continue;
      for (size_t i = 0; i < regions[r].size(); ++i) {
        integrated.row(regions[r][i]) = field.end_positions.row(static_cast<Eigen::Index>(i));
        field_of_vertex[static_cast<size_t>(regions[r][i])] = static_cast<int>(timed.size());
      }
      timed.push_back(std::move(field.field));
    }

    start = Clock::now();
    Candidate integrated_candidate = current;
    integrated_candidate.move_to(integrated);
    report.new_faces_after_integration = integrated_candidate.new_face_count();
    Eigen::MatrixX3d result = integrated;
    if (options.reproduction_rings >= 0) {
      // Faces the blend makes intersect are where it folds a corrected region onto the target's
      // shape, so the integrated result is kept around them too and the blend moves away.
      ReproductionSettings settings;
      settings.keep_rings = options.reproduction_rings;
      settings.blend_rings = options.blend_rings;
      settings.attempts = kReproductionAttempts;
      const FaceTest new_faces = [&](const Eigen::Ref<const Eigen::MatrixX3d>& pose) {
        return integrated_candidate.new_faces_if(pose);
      };
      Reproduction reproduction =
          reproduce_target(integrated, context.target, classification.near_intersections, context.faces,
                           context.neighbours, settings, new_faces, integrated_candidate.new_faces());
      report.reproduction_skipped = !reproduction.pose;
      if (reproduction.pose) {
        result = std::move(*reproduction.pose);
        report.reproduced_vertices = reproduction.reproduced_vertices;
      }
    }
    report.seconds.reproduction = seconds_since(start);

    stage.regions = static_cast<int>(timed.size());
    stage.vertices = static_cast<int>(differing_vertices(result, context.target).size());
    stage.details = {{"centers", report.centers()},
                     {"constraints", report.constraints()},
                     {"region_vertices", report.region_vertices},
                     {"new_faces_after_integration", report.new_faces_after_integration}};
    context.field = FieldOutcome{integrated,
                                 PathLines(context.reference, trajectories, std::move(timed), std::move(field_of_vertex),
                                           context.device, options.integration)};
    Candidate corrected = std::move(integrated_candidate);
    corrected.move_to(result);
    return corrected;
  }
};

}  // namespace

std::unique_ptr<RepairStage> make_field_stage() { return std::make_unique<FieldStage>(); }

}  // namespace posekit::detail
