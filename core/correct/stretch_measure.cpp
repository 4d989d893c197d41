#include "correct/stretch_measure.hpp"

#include <posekit/geometry.hpp>
#include <posekit/topology.hpp>

namespace posekit::detail {
namespace {

// Edges shorter than this fraction of the reference's mean edge length count as that long.
constexpr double kShortestStretchedEdge = 0.25;

}  // namespace

StretchMeasure::StretchMeasure(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                               const Eigen::Ref<const Eigen::MatrixX3d>& target,
                               const Eigen::Ref<const Eigen::MatrixX3i>& faces)
    : reference_(reference), target_(target), faces_(faces) {
  const Eigen::VectorXd lengths = edge_lengths(reference, edge_map(faces).edges);
  shortest_ = lengths.size() > 0 ? kShortestStretchedEdge * lengths.mean() : 0.0;
}

Eigen::VectorXd StretchMeasure::per_face(const Eigen::Ref<const Eigen::MatrixX3d>& pose) const {
  return edge_stretch(pose, reference_, target_, faces_, shortest_);
}

std::vector<int> StretchMeasure::stretched_faces(const Eigen::Ref<const Eigen::MatrixX3d>& pose, double factor) const {
  const Eigen::VectorXd stretch = per_face(pose);
  std::vector<int> faces;
  for (Eigen::Index f = 0; f < stretch.size(); ++f) {
    if (stretch(f) > factor) faces.push_back(static_cast<int>(f));
  }
  return faces;
}

int StretchMeasure::count(const Eigen::Ref<const Eigen::MatrixX3d>& pose, double factor) const {
  return static_cast<int>((per_face(pose).array() > factor).count());
}

}  // namespace posekit::detail
