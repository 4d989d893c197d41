#include "pose_highlights.hpp"

#include <posekit/self_intersections.hpp>
#include <posekit/vertex_regions.hpp>

#include <algorithm>
#include <iterator>

namespace posekit::report {

std::vector<FaceSet> intersection_sets(const std::vector<int>& intersecting, const std::vector<int>& reference_intersecting) {
  std::vector<int> shared;
  std::set_intersection(intersecting.begin(), intersecting.end(), reference_intersecting.begin(),
                        reference_intersecting.end(), std::back_inserter(shared));
  std::vector<int> fresh = new_intersecting_faces(intersecting, reference_intersecting);
  std::vector<FaceSet> sets;
  if (!shared.empty()) {
    const std::string count = std::to_string(shared.size());
    sets.push_back({std::move(shared), kReferenceIntersectionColour, count + " intersecting as in the reference"});
  }
  if (!fresh.empty()) {
    const std::string count = std::to_string(fresh.size());
    sets.push_back({std::move(fresh), kNewIntersectionColour, count + " new intersecting faces"});
  }
  return sets;
}

Eigen::VectorXd moved_fraction(const Eigen::Ref<const Eigen::MatrixX3d>& from, const Eigen::Ref<const Eigen::MatrixX3d>& to,
                               double diagonal) {
  return (to - from).rowwise().norm() / (diagonal > 0.0 ? diagonal : 1.0);
}

std::vector<Region> moved_regions(const Eigen::VectorXd& moved, const AdjacencyLists& neighbours,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& pose, int limit) {
  std::vector<char> flagged(static_cast<size_t>(moved.size()));
  for (Eigen::Index v = 0; v < moved.size(); ++v) flagged[static_cast<size_t>(v)] = moved(v) > 0.0;
  const std::vector<std::vector<int>> sets = connected_sets(flagged, neighbours);
  std::vector<Region> regions;
  for (const std::vector<int>& set : sets) {
    if (static_cast<int>(regions.size()) == limit) break;
    Eigen::Vector3d low = pose.row(set.front()).transpose();
    Eigen::Vector3d high = low;
    double largest = 0.0;
    for (const int v : set) {
      low = low.cwiseMin(pose.row(v).transpose());
      high = high.cwiseMax(pose.row(v).transpose());
      largest = std::max(largest, moved(v));
    }
    const std::string label = std::to_string(set.size()) + " vertices, moved up to " +
                              format_number(100.0 * largest, 2) + " % of the diagonal";
    regions.push_back({label, 0.5 * (low + high), std::max(0.5 * (high - low).norm(), 1e-12)});
  }
  return regions;
}

}  // namespace posekit::report
