// A closed test surface: the icosahedron subdivided and projected onto the unit sphere.
#pragma once

#include <posekit/mesh.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace posekit::testing {

/// Unit sphere: an icosahedron subdivided `levels` times, vertices projected onto the sphere.
inline Mesh icosphere(int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::RowVector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Eigen::RowVector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      v.push_back((0.5 * (v[static_cast<size_t>(a)] + v[static_cast<size_t>(b)])).normalized());
      const int index = static_cast<int>(v.size()) - 1;
      middle[key] = index;
      return index;
    };
    std::vector<Eigen::RowVector3i> finer;
    for (const auto& face : f) {
      const int a = mid(face(0), face(1)), b = mid(face(1), face(2)), c = mid(face(2), face(0));
      finer.push_back({face(0), a, c});
      finer.push_back({face(1), b, a});
      finer.push_back({face(2), c, b});
      finer.push_back({a, b, c});
    }
    f = std::move(finer);
  }
  Mesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  mesh.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (size_t i = 0; i < v.size(); ++i) mesh.vertices.row(static_cast<Eigen::Index>(i)) = v[i];
  for (size_t i = 0; i < f.size(); ++i) mesh.faces.row(static_cast<Eigen::Index>(i)) = f[i];
  return mesh;
}

}  // namespace posekit::testing
