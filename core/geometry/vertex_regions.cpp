#include <posekit/vertex_regions.hpp>

#include <algorithm>
#include <numeric>
#include <utility>

namespace posekit {

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

std::vector<char> face_vertices(const std::vector<int>& face_list, const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                size_t vertex_count) {
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

std::vector<char> faces_within(const std::vector<char>& flagged, const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  std::vector<char> inside(static_cast<size_t>(faces.rows()), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    inside[static_cast<size_t>(f)] = flagged[static_cast<size_t>(faces(f, 0))] != 0 &&
                                     flagged[static_cast<size_t>(faces(f, 1))] != 0 &&
                                     flagged[static_cast<size_t>(faces(f, 2))] != 0;
  }
  return inside;
}

bool touches(const std::vector<char>& flagged, const std::vector<int>& face_list,
             const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
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

std::vector<char> with_cut_off_parts(std::vector<char> region, const AdjacencyLists& neighbours) {
  std::vector<int> piece_of(region.size(), -1);
  int pieces = 0;
  for (const std::vector<int>& piece : connected_sets(std::vector<char>(region.size(), 1), neighbours)) {
    for (int v : piece) piece_of[static_cast<size_t>(v)] = pieces;
    ++pieces;
  }
  std::vector<char> outside(region.size(), 0);
  for (size_t v = 0; v < region.size(); ++v) outside[v] = region[v] == 0 ? 1 : 0;
  std::vector<char> kept_out(static_cast<size_t>(pieces), 0);
  // Largest first, so the first set met in a piece is the one that stays out.
  for (const std::vector<int>& set : connected_sets(outside, neighbours)) {
    char& piece_kept_out = kept_out[static_cast<size_t>(piece_of[static_cast<size_t>(set.front())])];
    if (piece_kept_out == 0) {
      piece_kept_out = 1;
      continue;
    }
    for (int v : set) region[static_cast<size_t>(v)] = 1;
  }
  return region;
}

std::vector<std::vector<int>> join_intersecting(const std::vector<std::vector<int>>& sets, const FacePairs& pairs,
                                                const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  int vertex_count = 0;
  for (const std::vector<int>& set : sets) {
    for (int v : set) vertex_count = std::max(vertex_count, v + 1);
  }
  std::vector<int> set_of(static_cast<size_t>(vertex_count), -1);
  for (size_t k = 0; k < sets.size(); ++k) {
    for (int v : sets[k]) set_of[static_cast<size_t>(v)] = static_cast<int>(k);
  }
  std::vector<int> parent(sets.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int k) {
    while (parent[static_cast<size_t>(k)] != k) {
      k = parent[static_cast<size_t>(k)] = parent[static_cast<size_t>(parent[static_cast<size_t>(k)])];
    }
    return k;
  };
  // The set of a face: that of its first corner in some set.
  const auto set_of_face = [&](int f) {
    for (int c = 0; c < 3; ++c) {
      const int v = faces(f, c);
      if (v < vertex_count && set_of[static_cast<size_t>(v)] >= 0) return set_of[static_cast<size_t>(v)];
    }
    return -1;
  };
  for (const auto& [f, g] : pairs) {
    const int a = set_of_face(f);
    const int b = set_of_face(g);
    if (a >= 0 && b >= 0) parent[static_cast<size_t>(root(a))] = root(b);
  }
  std::vector<std::vector<int>> joined(sets.size());
  for (size_t k = 0; k < sets.size(); ++k) {
    std::vector<int>& into = joined[static_cast<size_t>(root(static_cast<int>(k)))];
    into.insert(into.end(), sets[k].begin(), sets[k].end());
  }
  joined.erase(std::remove_if(joined.begin(), joined.end(), [](const auto& r) { return r.empty(); }), joined.end());
  std::stable_sort(joined.begin(), joined.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return joined;
}

}  // namespace posekit
