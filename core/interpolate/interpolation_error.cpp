#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/interpolation_error.hpp>
#include <posekit/rigid_motion.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

InterpolationErrorMeter::InterpolationErrorMeter(const PoseSet& poses) : poses_(poses) {
  if (poses.pose_count() == 0) throw ArgumentError("InterpolationErrorMeter: the pose set has no pose");
  faces_ = poses.faces();
  edges_ = edge_map(faces_);
  incident_faces_ = edge_faces(edges_);
  neighbours_ = vertex_neighbours(faces_, poses.vertex_count());
  coordinates_ = edge_space_coordinates(poses, edges_, incident_faces_);
  reference_areas_ = smallest_face_areas(poses);
}

InterpolationErrorMeter::InterpolationErrorMeter(const PoseSet& poses, EdgeMap edges, AdjacencyLists incident_faces,
                                                 AdjacencyLists neighbours, EdgeSpaceCoordinates coordinates)
    : poses_(poses),
      faces_(poses.faces()),
      edges_(std::move(edges)),
      incident_faces_(std::move(incident_faces)),
      neighbours_(std::move(neighbours)),
      coordinates_(std::move(coordinates)) {
  if (poses.pose_count() == 0) throw ArgumentError("InterpolationErrorMeter: the pose set has no pose");
  if (coordinates_.edge_count() != edges_.edges.rows() || edges_.face_edges.rows() != faces_.rows() ||
      neighbours_.item_count() != poses.vertex_count()) {
    throw ArgumentError("InterpolationErrorMeter: the topology or edge-space coordinates do not match the poses");
  }
  reference_areas_ = smallest_face_areas(poses);
}

int InterpolationErrorMeter::flipped_faces(const Eigen::Ref<const Eigen::MatrixX3d>& result) const {
  const int vertex_count = poses_.vertex_count();
  const int face_count = static_cast<int>(faces_.rows());
  const Eigen::MatrixX3d result_normals = face_normals(result, faces_);
  std::vector<char> agrees(static_cast<size_t>(face_count), 0);
  std::vector<Eigen::Matrix3d> turns(static_cast<size_t>(vertex_count));
  for (int k = 0; k < poses_.pose_count(); ++k) {
    const Eigen::MatrixX3d& pose = poses_.pose(k);
    // The rotation that best moves each vertex's one-ring (with the vertex) from the pose onto the result.
    tbb::parallel_for(0, vertex_count, [&](int v) {
      const IndexRange ring = neighbours_[v];
      Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
      for (const int w : ring) {
        covariance += (result.row(w) - result.row(v)).transpose() * (pose.row(w) - pose.row(v));
      }
      turns[static_cast<size_t>(v)] = nearest_rotation(covariance);
    });
    const Eigen::MatrixX3d normals = face_normals(pose, faces_);
    tbb::parallel_for(0, face_count, [&](int f) {
      double agreement = 0.0;
      for (int corner = 0; corner < 3; ++corner) {
        agreement += result_normals.row(f).dot(normals.row(f) * turns[static_cast<size_t>(faces_(f, corner))].transpose());
      }
      if (agreement >= 0.0) agrees[static_cast<size_t>(f)] = 1;
    });
  }
  int flipped = 0;
  for (int f = 0; f < face_count; ++f) {
    // Degenerate faces have no normal to flip.
    if (!agrees[static_cast<size_t>(f)] && result_normals.row(f).squaredNorm() > 0.0) ++flipped;
  }
  return flipped;
}

void InterpolationErrorMeter::check_arguments(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                              const Eigen::VectorXd& weights) const {
  if (weights.size() != coordinates_.pose_count()) {
    throw ArgumentError("interpolation error: " + std::to_string(weights.size()) + " weights for " +
                        std::to_string(coordinates_.pose_count()) + " poses");
  }
  check_face_indices(faces_, static_cast<int>(result.rows()));
}

InterpolationError InterpolationErrorMeter::measure(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                                    const Eigen::VectorXd& weights) const {
  check_arguments(result, weights);
  InterpolationError error;
  if (!result.allFinite()) {
    error.finite = false;
    return error;
  }
  const Eigen::VectorXd target_angles = coordinates_.combined_angles(weights);
  const Eigen::VectorXd relative_length_errors = edge_length_errors(result, weights);
  const Eigen::VectorXd angles = dihedral_angles(result, faces_, edges_, incident_faces_);
  const int edge_count = coordinates_.edge_count();
  std::vector<double> length_errors;
  std::vector<double> angle_errors;
  length_errors.reserve(static_cast<size_t>(edge_count));
  angle_errors.reserve(static_cast<size_t>(edge_count));
  for (int e = 0; e < edge_count; ++e) {
    if (!std::isnan(relative_length_errors(e))) length_errors.push_back(relative_length_errors(e));
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
  error.flipped_faces = flipped_faces(result);
  return error;
}

Eigen::VectorXd InterpolationErrorMeter::edge_length_errors(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                                            const Eigen::VectorXd& weights) const {
  const Eigen::VectorXd target_lengths = coordinates_.combined_lengths(weights);
  const Eigen::VectorXd lengths = edge_lengths(result, edges_.edges);
  Eigen::VectorXd errors(lengths.size());
  for (Eigen::Index e = 0; e < lengths.size(); ++e) {
    errors(e) = target_lengths(e) > 0.0 ? std::abs(lengths(e) - target_lengths(e)) / target_lengths(e)
                                        : std::numeric_limits<double>::quiet_NaN();
  }
  return errors;
}

Eigen::VectorXd InterpolationErrorMeter::vertex_edge_length_errors(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                                                                   const Eigen::VectorXd& weights) const {
  check_arguments(result, weights);
  const Eigen::VectorXd errors = edge_length_errors(result, weights);
  Eigen::VectorXd largest = Eigen::VectorXd::Zero(result.rows());
  for (Eigen::Index e = 0; e < errors.size(); ++e) {
    if (!(errors(e) > 0.0)) continue;  // NaN or 0
    for (int end = 0; end < 2; ++end) {
      double& value = largest(edges_.edges(e, end));
      value = std::max(value, errors(e));
    }
  }
  return largest;
}

InterpolationError interpolation_error(const Eigen::Ref<const Eigen::MatrixX3d>& result, const PoseSet& poses,
                                       const Eigen::VectorXd& weights) {
  return InterpolationErrorMeter(poses).measure(result, weights);
}

}  // namespace posekit
