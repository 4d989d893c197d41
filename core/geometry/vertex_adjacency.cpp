#include <posekit/topology.hpp>

#include <algorithm>
#include <utility>
#include <vector>

namespace posekit {

AdjacencyLists vertex_neighbours(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count) {
  check_face_indices(faces, vertex_count);
  const Eigen::Index face_count = faces.rows();

  // Every corner names its two face neighbours; duplicates (each interior edge is seen from two faces)
  // are removed per list afterwards.
  std::vector<int> offsets(static_cast<size_t>(vertex_count) + 1, 0);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) offsets[static_cast<size_t>(faces(f, corner)) + 1] += 2;
  }
  for (size_t v = 0; v < static_cast<size_t>(vertex_count); ++v) offsets[v + 1] += offsets[v];

  std::vector<int> candidates(static_cast<size_t>(offsets.back()));
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const auto vertex = static_cast<size_t>(faces(f, corner));
      candidates[static_cast<size_t>(fill[vertex]++)] = faces(f, (corner + 1) % 3);
      candidates[static_cast<size_t>(fill[vertex]++)] = faces(f, (corner + 2) % 3);
    }
  }

  std::vector<int> compact_offsets(static_cast<size_t>(vertex_count) + 1, 0);
  std::vector<int> indices;
  indices.reserve(candidates.size() / 2);
  for (size_t v = 0; v < static_cast<size_t>(vertex_count); ++v) {
    auto first = candidates.begin() + offsets[v];
    auto last = candidates.begin() + offsets[v + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    for (auto it = first; it != last; ++it) {
      if (*it != static_cast<int>(v)) indices.push_back(*it);
    }
    compact_offsets[v + 1] = static_cast<int>(indices.size());
  }
  return AdjacencyLists(std::move(compact_offsets), std::move(indices));
}

AdjacencyLists vertex_faces(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count) {
  check_face_indices(faces, vertex_count);
  const Eigen::Index face_count = faces.rows();

  std::vector<int> offsets(static_cast<size_t>(vertex_count) + 1, 0);
  std::vector<int> last_face(static_cast<size_t>(vertex_count), -1);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const auto vertex = static_cast<size_t>(faces(f, corner));
      if (last_face[vertex] == f) continue;  // a face that repeats the vertex counts once
      last_face[vertex] = static_cast<int>(f);
      ++offsets[vertex + 1];
    }
  }
  for (size_t v = 0; v < static_cast<size_t>(vertex_count); ++v) offsets[v + 1] += offsets[v];

  std::vector<int> indices(static_cast<size_t>(offsets.back()));
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  std::fill(last_face.begin(), last_face.end(), -1);
  for (Eigen::Index f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const auto vertex = static_cast<size_t>(faces(f, corner));
      if (last_face[vertex] == f) continue;
      last_face[vertex] = static_cast<int>(f);
      indices[static_cast<size_t>(fill[vertex]++)] = static_cast<int>(f);
    }
  }
  return AdjacencyLists(std::move(offsets), std::move(indices));
}

}  // namespace posekit
