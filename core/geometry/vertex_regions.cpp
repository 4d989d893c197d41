#include "correct/vertex_regions.hpp"

#include <algorithm>
#include <utility>

namespace posekit::detail {

std::vector<int> ring_distances(const std::vector<char>& flagged, const AdjacencyLists& neighbours, int limit) {
  std::vector<int> distance(flagged.size(), -1);
  std::vector<int> frontier;
  for (int v = 0; v < static_cast<int>(flagged.size()); ++v) {
    if (flagged[static_cast<size_t>(v)] != 0) {
      distance[static_cast<size_t>(v)] = 0;
      frontier.push_back(v);
    }
  }
  for (int ring = 1; ring <= limit && !frontier.empty(); ++ring) {
    std::vector<int> next;
    for (int v : frontier) {
      for (int w : neighbours[v]) {
        if (distance[static_cast<size_t>(w)] >= 0) continue;
        distance[static_cast<size_t>(w)] = ring;
        next.push_back(w);
      }
    }
    frontier = std::move(next);
  }
  return distance;
}

std::vector<char> face_vertices(const std::vector<int>& face_list, const Eigen::MatrixX3i& faces, size_t vertex_count) {
  std::vector<char> flags(vertex_count, 0);
  for (int f : face_list) {
    for (int c = 0; c < 3; ++c) flags[static_cast<size_t>(faces(f, c))] = 1;
  }
  return flags;
}

std::vector<char> within_rings(const std::vector<char>& flagged, const AdjacencyLists& neighbours, int rings) {
  const std::vector<int> distance = ring_distances(flagged, neighbours, rings);
  std::vector<char> flags(flagged.size(), 0);
  for (size_t v = 0; v < flags.size(); ++v) flags[v] = distance[v] >= 0 ? 1 : 0;
  return flags;
}

std::vector<char> faces_within(const std::vector<char>& flagged, const Eigen::MatrixX3i& faces) {
  std::vector<char> inside(static_cast<size_t>(faces.rows()), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    inside[static_cast<size_t>(f)] = flagged[static_cast<size_t>(faces(f, 0))] != 0 &&
                                     flagged[static_cast<size_t>(faces(f, 1))] != 0 &&
                                     flagged[static_cast<size_t>(faces(f, 2))] != 0;
  }
  return inside;
}

bool touches(const std::vector<char>& flagged, const std::vector<int>& face_list, const Eigen::MatrixX3i& faces) {
  for (int f : face_list) {
    for (int c = 0; c < 3; ++c) {
      if (flagged[static_cast<size_t>(faces(f, c))] != 0) return true;
    }
  }
  return false;
}

std::vector<std::vector<int>> connected_sets(const std::vector<char>& flagged, const AdjacencyLists& neighbours) {
  std::vector<char> seen(flagged.size(), 0);
  std::vector<std::vector<int>> sets;
  for (int seed = 0; seed < static_cast<int>(flagged.size()); ++seed) {
    if (flagged[static_cast<size_t>(seed)] == 0 || seen[static_cast<size_t>(seed)] != 0) continue;
    std::vector<int> members{seed};
    seen[static_cast<size_t>(seed)] = 1;
    for (size_t next = 0; next < members.size(); ++next) {
      for (int w : neighbours[members[next]]) {
        if (flagged[static_cast<size_t>(w)] != 0 && seen[static_cast<size_t>(w)] == 0) {
          seen[static_cast<size_t>(w)] = 1;
          members.push_back(w);
        }
      }
    }
    sets.push_back(std::move(members));
  }
  std::stable_sort(sets.begin(), sets.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return sets;
}

}  // namespace posekit::detail
