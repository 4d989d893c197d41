#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/interpolation_error.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace posekit {
namespace {

constexpr double kDegreesPerRadian = 57.29577951308232;
// A face is collapsed below this fraction of its smallest input area; a hinge folded beyond this
// many degrees of error.
constexpr double kCollapsedAreaFraction = 0.25;
constexpr double kFoldedDegrees = 90.0;

// Nearest-rank percentile: the smallest value with at least `fraction` of all values at or below it.
double percentile(std::vector<double>& values, double fraction) {
  if (values.empty()) return 0.0;
  const auto count = static_cast<double>(values.size());
  auto rank = static_cast<size_t>(std::ceil(fraction * count));
  rank = std::min(std::max<size_t>(rank, 1), values.size());
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank - 1), values.end());
  return values[rank - 1];
}

ErrorPercentiles summarize(std::vector<double> values) {
  ErrorPercentiles result;
  if (values.empty()) return result;
  result.max = *std::max_element(values.begin(), values.end());
  result.p999 = percentile(values, 0.999);
  result.p99 = percentile(values, 0.99);
  return result;
}

}  // namespace

Eigen::VectorXd smallest_face_areas(const PoseSet& poses) {
  if (poses.pose_count() == 0) throw ArgumentError("smallest_face_areas: the pose set has no pose");
  Eigen::VectorXd areas = face_areas(poses.pose(0), poses.faces());
  for (int k = 1; k < poses.pose_count(); ++k) areas = areas.cwiseMin(face_areas(poses.pose(k), poses.faces()));
  return areas;
}

InterpolationErrorMeter::InterpolationErrorMeter(const PoseSet& poses) {
  if (poses.pose_count() == 0) throw ArgumentError("InterpolationErrorMeter: the pose set has no pose");
  faces_ = poses.faces();
  edges_ = edge_map(faces_);
  incident_faces_ = edge_faces(edges_);
  coordinates_ = edge_space_coordinates(poses, edges_, incident_faces_);
  reference_areas_ = smallest_face_areas(poses);
}

InterpolationErrorMeter::InterpolationErrorMeter(Eigen::MatrixX3i faces, EdgeMap edges, AdjacencyLists incident_faces,
                                                 EdgeSpaceCoordinates coordinates, Eigen::VectorXd reference_areas)
    : faces_(std::move(faces)),
      edges_(std::move(edges)),
      incident_faces_(std::move(incident_faces)),
      coordinates_(std::move(coordinates)),
      reference_areas_(std::move(reference_areas)) {
  if (coordinates_.edge_count() != edges_.edges.rows() || reference_areas_.size() != faces_.rows()) {
    throw ArgumentError("InterpolationErrorMeter: edge-space coordinates or areas do not match the mesh");
  }
}

InterpolationError InterpolationErrorMeter::measure(const Eigen::MatrixX3d& result, const Eigen::VectorXd& weights) const {
  if (weights.size() != coordinates_.pose_count()) {
    throw ArgumentError("interpolation error: " + std::to_string(weights.size()) + " weights for " +
                        std::to_string(coordinates_.pose_count()) + " poses");
  }
  check_face_indices(faces_, static_cast<int>(result.rows()));
  InterpolationError error;
  if (!result.allFinite()) {
    error.finite = false;
    return error;
  }
  const Eigen::VectorXd target_lengths = coordinates_.combined_lengths(weights);
  const Eigen::VectorXd target_angles = coordinates_.combined_angles(weights);
  const Eigen::VectorXd lengths = edge_lengths(result, edges_.edges);
  const Eigen::VectorXd angles = dihedral_angles(result, faces_, edges_, incident_faces_);
  const int edge_count = coordinates_.edge_count();
  std::vector<double> length_errors;
  std::vector<double> angle_errors;
  length_errors.reserve(static_cast<size_t>(edge_count));
  angle_errors.reserve(static_cast<size_t>(edge_count));
  for (int e = 0; e < edge_count; ++e) {
    if (target_lengths(e) > 0.0) length_errors.push_back(std::abs(lengths(e) - target_lengths(e)) / target_lengths(e));
    if (!coordinates_.hinge[static_cast<size_t>(e)]) continue;
    const double degrees = std::isfinite(angles(e)) ? std::abs(wrap_angle(angles(e) - target_angles(e))) * kDegreesPerRadian
                                                    : 180.0;
    angle_errors.push_back(degrees);
    if (degrees > kFoldedDegrees) ++error.folded_edges;
  }
  error.edge_length = summarize(std::move(length_errors));
  error.dihedral_degrees = summarize(std::move(angle_errors));
  const Eigen::VectorXd areas = face_areas(result, faces_);
  for (Eigen::Index f = 0; f < areas.size(); ++f) {
    if (areas(f) < kCollapsedAreaFraction * reference_areas_(f)) ++error.collapsed_faces;
  }
  return error;
}

InterpolationError interpolation_error(const Eigen::MatrixX3d& result, const PoseSet& poses, const Eigen::VectorXd& weights) {
  return InterpolationErrorMeter(poses).measure(result, weights);
}

}  // namespace posekit
