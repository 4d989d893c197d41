#include <posekit/error.hpp>
#include <posekit/topology.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace posekit {

EdgeMap edge_map(const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const Eigen::Index face_count = faces.rows();
  if (faces.size() > 0 && faces.minCoeff() < 0) {
    throw ArgumentError("edge_map: faces contain a negative vertex index");
  }
  if (face_count > std::numeric_limits<int>::max() / 3) {
    throw ArgumentError("edge_map: too many faces (" + std::to_string(face_count) + ")");
  }

  // One sortable key per face side: the sorted vertex pair packed into 64 bits, then the side's slot
  // (3 * face + corner), so equal edges end up adjacent and ties keep face order.
  std::vector<std::pair<std::uint64_t, int>> sides;
  sides.reserve(static_cast<size_t>(face_count) * 3);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const auto a = static_cast<std::uint32_t>(faces(f, corner));
      const auto b = static_cast<std::uint32_t>(faces(f, (corner + 1) % 3));
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32U) | std::max(a, b);
      sides.emplace_back(key, static_cast<int>(f * 3 + corner));
    }
  }
  std::sort(sides.begin(), sides.end());

  EdgeMap result;
  result.face_edges.resize(face_count, 3);
  std::vector<std::uint64_t> unique_keys;
  unique_keys.reserve(sides.size() / 2 + 1);
  for (const auto& [key, slot] : sides) {
    if (unique_keys.empty() || unique_keys.back() != key) unique_keys.push_back(key);
    result.face_edges(slot / 3, slot % 3) = static_cast<int>(unique_keys.size()) - 1;
  }
  result.edges.resize(static_cast<Eigen::Index>(unique_keys.size()), 2);
  for (size_t e = 0; e < unique_keys.size(); ++e) {
    result.edges(static_cast<Eigen::Index>(e), 0) = static_cast<int>(unique_keys[e] >> 32U);
    result.edges(static_cast<Eigen::Index>(e), 1) = static_cast<int>(unique_keys[e] & 0xffffffffU);
  }
  return result;
}

AdjacencyLists edge_faces(const EdgeMap& edges) {
  const auto edge_count = static_cast<int>(edges.edges.rows());
  const Eigen::Index face_count = edges.face_edges.rows();
  if (edges.face_edges.size() > 0 &&
      (edges.face_edges.minCoeff() < 0 || edges.face_edges.maxCoeff() >= edge_count)) {
    throw ArgumentError("edge_faces: face_edges refers to an edge outside [0, " + std::to_string(edge_count) +
                        ")");
  }

  // A face lists an edge once even if two of its sides coincide (a repeated vertex).
  auto side_is_repeat = [&](Eigen::Index f, int corner) {
    for (int earlier = 0; earlier < corner; ++earlier) {
      if (edges.face_edges(f, earlier) == edges.face_edges(f, corner)) return true;
    }
    return false;
  };

  std::vector<int> offsets(static_cast<size_t>(edge_count) + 1, 0);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      if (!side_is_repeat(f, corner)) ++offsets[static_cast<size_t>(edges.face_edges(f, corner)) + 1];
    }
  }
  for (size_t e = 0; e < static_cast<size_t>(edge_count); ++e) offsets[e + 1] += offsets[e];

  std::vector<int> indices(static_cast<size_t>(offsets.back()));
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      if (side_is_repeat(f, corner)) continue;
      const auto edge = static_cast<size_t>(edges.face_edges(f, corner));
      indices[static_cast<size_t>(fill[edge]++)] = static_cast<int>(f);
    }
  }
  return AdjacencyLists(std::move(offsets), std::move(indices));
}

}  // namespace posekit
