#include "correct/vertex_classification.hpp"

#include <posekit/error.hpp>
#include <posekit/self_intersections.hpp>
#include <posekit/topology.hpp>

namespace posekit::detail {

VertexClassification classify_vertices(const std::vector<FacePairs>& pairs_per_pose,
                                       const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                       const AdjacencyLists& neighbours, int rings,
                                       const std::vector<int>& user_excluded) {
  if (pairs_per_pose.size() < 2) throw ArgumentError("classification needs the reference and the target");
  if (rings < 0) throw ArgumentError("exclusion rings must be >= 0, got " + std::to_string(rings));
  const int vertex_count = neighbours.item_count();
  const std::vector<FacePairs>& frames = pairs_per_pose;
  VertexClassification result;
  std::vector<char> excluded(static_cast<size_t>(vertex_count), 0);
  std::vector<char> excluded_by_target(static_cast<size_t>(vertex_count), 0);
  result.unconstrained_in_frame.assign(frames.size(), std::vector<char>(static_cast<size_t>(vertex_count), 0));
  for (size_t frame = 0; frame < frames.size(); ++frame) {
    const std::vector<int> intersecting = faces_in_pairs(frames[frame]);
    const bool is_target = frame + 1 == frames.size();
    if (frame == 0) result.reference_intersecting = intersecting;
    if (is_target) result.target_intersecting = intersecting;
    for (int face : intersecting) {
      for (int corner = 0; corner < 3; ++corner) {
        excluded[static_cast<size_t>(faces(face, corner))] = 1;
        result.unconstrained_in_frame[frame][static_cast<size_t>(faces(face, corner))] = 1;
        if (is_target) excluded_by_target[static_cast<size_t>(faces(face, corner))] = 1;
      }
    }
  }
  const auto grow = [&](std::vector<char>& flags) {
    for (int ring = 0; ring < rings; ++ring) {
      std::vector<char> grown = flags;
      for (int v = 0; v < vertex_count; ++v) {
        if (!flags[static_cast<size_t>(v)]) continue;
        for (int neighbour : neighbours[v]) grown[static_cast<size_t>(neighbour)] = 1;
      }
      flags.swap(grown);
    }
  };
  grow(excluded);
  grow(excluded_by_target);
  for (std::vector<char>& flags : result.unconstrained_in_frame) grow(flags);
  result.near_intersections = excluded;
  // A vertex of a face that intersects somewhere on the way and not in the reference stays free even
  // where it also belongs to one of the reference's intersecting faces: pinned, it would carry the
  // reference's intersection onto its new face wherever the target slides it there.
  std::vector<char> on_new_face(static_cast<size_t>(vertex_count), 0);
  for (const FacePairs& pairs : frames) {
    for (int face : new_intersecting_faces(faces_in_pairs(pairs), result.reference_intersecting)) {
      for (int corner = 0; corner < 3; ++corner) on_new_face[static_cast<size_t>(faces(face, corner))] = 1;
    }
  }
  for (int face : result.reference_intersecting) {
    for (int corner = 0; corner < 3; ++corner) {
      if (on_new_face[static_cast<size_t>(faces(face, corner))]) continue;
      excluded[static_cast<size_t>(faces(face, corner))] = 0;
      for (std::vector<char>& flags : result.unconstrained_in_frame) flags[static_cast<size_t>(faces(face, corner))] = 0;
    }
  }
  result.in_transit.resize(static_cast<size_t>(vertex_count));
  for (int v = 0; v < vertex_count; ++v) {
    result.in_transit[static_cast<size_t>(v)] =
        excluded[static_cast<size_t>(v)] && !excluded_by_target[static_cast<size_t>(v)] ? 1 : 0;
  }
  for (int vertex : user_excluded) {
    if (vertex < 0 || vertex >= vertex_count) {
      throw ArgumentError("excluded vertex " + std::to_string(vertex) + " is outside [0, " +
                          std::to_string(vertex_count) + ")");
    }
    excluded[static_cast<size_t>(vertex)] = 1;
    result.near_intersections[static_cast<size_t>(vertex)] = 1;
    for (std::vector<char>& flags : result.unconstrained_in_frame) flags[static_cast<size_t>(vertex)] = 1;
  }
  result.constrained.resize(static_cast<size_t>(vertex_count));
  for (int v = 0; v < vertex_count; ++v) {
    result.constrained[static_cast<size_t>(v)] = excluded[static_cast<size_t>(v)] ? 0 : 1;
    result.excluded += excluded[static_cast<size_t>(v)];
  }
  return result;
}

}  // namespace posekit::detail
