#include "interpolate/edge_interpolation.hpp"
#include "interpolate/mixed_interpolation.hpp"

#include <posekit/error.hpp>
#include <posekit/interpolate.hpp>

#include <chrono>
#include <cmath>
#include <sstream>

namespace posekit {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

constexpr double kWeightSumTolerance = 1e-4;

void check_options(const InterpolationOptions& options, const PoseSet& poses) {
  if (poses.pose_count() < 2) {
    throw ArgumentError("interpolation needs at least two poses, got " + std::to_string(poses.pose_count()));
  }
  if (options.joint_width < 1 || options.joint_width > 100) {
    throw ArgumentError("joint width must lie in [1, 100], got " + std::to_string(options.joint_width));
  }
  if (options.joint_iterations < 0 || options.refinement_iterations < 0 || options.edge_iterations < 0 ||
      options.projection_passes < 0) {
    throw ArgumentError("iteration and pass counts must not be negative");
  }
  if (!(options.bending_weight > 0.0) || !std::isfinite(options.bending_weight)) {
    throw ArgumentError("bending weight must be positive and finite");
  }
  if (options.alignment_sweeps < 0) throw ArgumentError("alignment sweeps must not be negative");
  if (!(options.projection_hinge_weight >= 0.0) || !std::isfinite(options.projection_hinge_weight)) {
    throw ArgumentError("projection hinge weight must be finite and not negative");
  }
  if (options.face_parts.size() != 0) {
    if (options.face_parts.size() != poses.faces().rows()) {
      throw ArgumentError("face_parts has " + std::to_string(options.face_parts.size()) + " ids for " +
                          std::to_string(poses.faces().rows()) + " faces");
    }
    if (options.face_parts.minCoeff() < 0) throw ArgumentError("face_parts holds a negative part id");
  }
}

}  // namespace

std::string to_string(InterpolationMethod method) {
  switch (method) {
    case InterpolationMethod::mixit:
      return "mixit";
    case InterpolationMethod::edge:
      return "edge";
    case InterpolationMethod::vertex:
      return "vertex";
  }
  return "unknown";
}

InterpolationMethod interpolation_method_from_string(const std::string& name) {
  if (name == "mixit") return InterpolationMethod::mixit;
  if (name == "edge") return InterpolationMethod::edge;
  if (name == "vertex") return InterpolationMethod::vertex;
  throw ArgumentError("unknown interpolation method '" + name + "' (use mixit, edge or vertex)");
}

Eigen::VectorXd two_pose_weights(double t) {
  Eigen::VectorXd weights(2);
  weights << 1.0 - t, t;
  return weights;
}

Eigen::VectorXd normalized_weights(const Eigen::VectorXd& weights, int pose_count) {
  if (weights.size() != pose_count) {
    throw ArgumentError(std::to_string(weights.size()) + " weights for " + std::to_string(pose_count) +
                        " poses (give one weight per pose)");
  }
  if (!weights.allFinite()) throw ArgumentError("weights must be finite numbers");
  const double sum = weights.sum();
  if (std::abs(sum - 1.0) > kWeightSumTolerance) {
    std::ostringstream text;
    text.precision(12);
    text << "weights sum to " << sum << ", not 1";
    throw ArgumentError(text.str());
  }
  return weights / sum;
}

struct PoseInterpolator::State {
  PoseSet poses;
  InterpolationOptions options;
  EdgeMap edges;
  AdjacencyLists incident_faces;
  AdjacencyLists neighbours;
  EdgeSpaceCoordinates coordinates;
  std::unique_ptr<InterpolationErrorMeter> meter;
  Eigen::VectorXi face_parts;
  InterpolationLayout layout;
  PrecomputationTimes seconds;
  std::unique_ptr<interpolation::MixedInterpolation> mixed;
  std::unique_ptr<interpolation::EdgeInterpolation> edge;
};

PoseInterpolator::PoseInterpolator(PoseSet poses, const InterpolationOptions& options)
    : state_(std::make_unique<State>()) {
  check_options(options, poses);
  const auto start = Clock::now();
  State& s = *state_;
  s.poses = std::move(poses);
  s.options = options;
  auto stage = Clock::now();
  s.edges = edge_map(s.poses.faces());
  s.incident_faces = edge_faces(s.edges);
  s.neighbours = vertex_neighbours(s.poses.faces(), s.poses.vertex_count());
  s.coordinates = edge_space_coordinates(s.poses, s.edges, s.incident_faces);
  s.meter = std::make_unique<InterpolationErrorMeter>(s.poses, s.edges, s.incident_faces, s.neighbours, s.coordinates);
  s.seconds.edge_space = seconds_since(stage);
  s.layout.edge_dimension = 2LL * s.coordinates.edge_count();

  if (options.method == InterpolationMethod::mixit) {
    stage = Clock::now();
    if (options.face_parts.size() != 0) {
      s.face_parts = connected_parts(options.face_parts, s.edges, s.incident_faces);
    } else {
      s.face_parts = segment_rigid_parts(s.poses, options.segmentation);
    }
    s.seconds.segmentation = seconds_since(stage);
    s.mixed = std::make_unique<interpolation::MixedInterpolation>(s.poses, s.edges, s.incident_faces, s.neighbours,
                                                                  s.coordinates, s.face_parts, options, s.seconds);
    s.layout = s.mixed->layout();
  } else if (options.method == InterpolationMethod::edge) {
    s.edge = std::make_unique<interpolation::EdgeInterpolation>(s.poses, s.edges, s.incident_faces, s.coordinates,
                                                                options, s.seconds);
  }
  s.seconds.total = seconds_since(start);
}

PoseInterpolator::~PoseInterpolator() = default;
PoseInterpolator::PoseInterpolator(PoseInterpolator&&) noexcept = default;
PoseInterpolator& PoseInterpolator::operator=(PoseInterpolator&&) noexcept = default;

Eigen::MatrixX3d PoseInterpolator::interpolate(const Eigen::VectorXd& weights_in, InterpolationStepReport* report) {
  State& s = *state_;
  const Eigen::VectorXd weights = normalized_weights(weights_in, s.poses.pose_count());
  InterpolationStepReport local;
  InterpolationStepReport& step = report != nullptr ? *report : local;
  step = InterpolationStepReport{};
  if (s.mixed) return s.mixed->interpolate(weights, step);
  if (s.edge) return s.edge->interpolate(weights, step);
  const auto start = Clock::now();
  Eigen::MatrixX3d result = weights(0) * s.poses.pose(0);
  for (int k = 1; k < s.poses.pose_count(); ++k) result += weights(k) * s.poses.pose(k);
  step.seconds.blend = seconds_since(start);
  step.seconds.total = step.seconds.blend;
  return result;
}

InterpolationError PoseInterpolator::error(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                           const Eigen::VectorXd& weights) const {
  return state_->meter->measure(result, normalized_weights(weights, state_->poses.pose_count()));
}

Eigen::VectorXd PoseInterpolator::vertex_edge_length_errors(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                                            const Eigen::VectorXd& weights) const {
  return state_->meter->vertex_edge_length_errors(result, normalized_weights(weights, state_->poses.pose_count()));
}

const PoseSet& PoseInterpolator::poses() const { return state_->poses; }
const InterpolationOptions& PoseInterpolator::options() const { return state_->options; }
const Eigen::VectorXi& PoseInterpolator::face_parts() const { return state_->face_parts; }
const InterpolationLayout& PoseInterpolator::layout() const { return state_->layout; }
const PrecomputationTimes& PoseInterpolator::precomputation_seconds() const { return state_->seconds; }

Eigen::MatrixX3d interpolate_poses(const PoseSet& poses, const Eigen::VectorXd& weights,
                                   const InterpolationOptions& options, InterpolationReport* report) {
  PoseInterpolator interpolator(poses, options);
  InterpolationStepReport step;
  Eigen::MatrixX3d result = interpolator.interpolate(weights, &step);
  if (report != nullptr) {
    report->layout = interpolator.layout();
    report->precomputation = interpolator.precomputation_seconds();
    report->step = step;
    report->error = interpolator.error(result, weights);
  }
  return result;
}

}  // namespace posekit
