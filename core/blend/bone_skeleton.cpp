#include "blend/bone_skeleton.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>
#include <utility>

namespace posekit::detail {
namespace {

struct BonePair {
  int a = 0;
  int b = 0;
  Eigen::Vector3d boundary = Eigen::Vector3d::Zero();  // sum of the crossing edges' midpoints
  int edges = 0;
};

int find_root(std::vector<int>& set, int x) {
  while (set[static_cast<size_t>(x)] != x) {
    set[static_cast<size_t>(x)] = set[static_cast<size_t>(set[static_cast<size_t>(x)])];
    x = set[static_cast<size_t>(x)];
  }
  return x;
}

}  // namespace

BoneSkeleton bone_skeleton(const Eigen::MatrixX3d& rest, const AdjacencyLists& neighbours, const std::vector<int>& primary,
                           const Eigen::VectorXd& mass, const std::vector<RigidMotion>& motions, int bones, int examples) {
  // Bone pairs that meet on the surface, with the midpoint of the edges between them.
  std::map<std::pair<int, int>, BonePair> pairs;
  for (int u = 0; u < neighbours.item_count(); ++u) {
    for (int v : neighbours[u]) {
      if (v <= u) continue;
      int a = primary[static_cast<size_t>(u)];
      int b = primary[static_cast<size_t>(v)];
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      BonePair& pair = pairs[{a, b}];
      pair.a = a;
      pair.b = b;
      pair.boundary += 0.5 * (rest.row(u) + rest.row(v)).transpose();
      ++pair.edges;
    }
  }

  // The joint of a pair: the point c minimizing sum_k |(R_a - R_b) c + t_a - t_b|^2; a small pull
  // towards the boundary fixes c along a hinge's axis, which the motions leave free.
  const double pull = 1e-3 * std::max(1, examples - 1);
  std::vector<std::tuple<double, int, int, Eigen::Vector3d>> candidates;
  for (const auto& entry : pairs) {
    const BonePair& pair = entry.second;
    const Eigen::Vector3d middle = pair.boundary / pair.edges;
    Eigen::Matrix3d normal = pull * Eigen::Matrix3d::Identity();
    Eigen::Vector3d side = pull * middle;
    for (int k = 1; k < examples; ++k) {
      const RigidMotion& ma = motions[static_cast<size_t>(k * bones + pair.a)];
      const RigidMotion& mb = motions[static_cast<size_t>(k * bones + pair.b)];
      const Eigen::Matrix3d dr = ma.leftCols<3>() - mb.leftCols<3>();
      const Eigen::Vector3d dt = ma.col(3) - mb.col(3);
      normal += dr.transpose() * dr;
      side -= dr.transpose() * dt;
    }
    const Eigen::Vector3d joint = normal.ldlt().solve(side);
    double residual = 0.0;
    for (int k = 1; k < examples; ++k) {
      const RigidMotion& ma = motions[static_cast<size_t>(k * bones + pair.a)];
      const RigidMotion& mb = motions[static_cast<size_t>(k * bones + pair.b)];
      residual += ((ma.leftCols<3>() - mb.leftCols<3>()) * joint + ma.col(3) - mb.col(3)).squaredNorm();
    }
    candidates.emplace_back(std::sqrt(residual / std::max(1, examples - 1)), pair.a, pair.b, joint);
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });

  // Minimum spanning forest (Kruskal).
  std::vector<int> set(static_cast<size_t>(bones));
  std::iota(set.begin(), set.end(), 0);
  std::vector<std::vector<std::pair<int, Eigen::Vector3d>>> tree(static_cast<size_t>(bones));
  for (const auto& [cost, a, b, joint] : candidates) {
    const int ra = find_root(set, a);
    const int rb = find_root(set, b);
    if (ra == rb) continue;
    set[static_cast<size_t>(ra)] = rb;
    tree[static_cast<size_t>(a)].emplace_back(b, joint);
    tree[static_cast<size_t>(b)].emplace_back(a, joint);
  }

  // Bone masses and centroids, for the roots.
  Eigen::VectorXd bone_mass = Eigen::VectorXd::Zero(bones);
  Eigen::MatrixX3d centroid = Eigen::MatrixX3d::Zero(bones, 3);
  for (Eigen::Index i = 0; i < rest.rows(); ++i) {
    const int j = primary[static_cast<size_t>(i)];
    bone_mass(j) += mass(i);
    centroid.row(j) += mass(i) * rest.row(i);
  }

  BoneSkeleton skeleton;
  skeleton.parents.assign(static_cast<size_t>(bones), -2);
  skeleton.joints = Eigen::MatrixX3d::Zero(bones, 3);
  skeleton.jointed.assign(static_cast<size_t>(bones), {});
  std::vector<int> order(static_cast<size_t>(bones));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return bone_mass(x) > bone_mass(y); });
  for (int root : order) {
    if (skeleton.parents[static_cast<size_t>(root)] != -2) continue;
    skeleton.parents[static_cast<size_t>(root)] = -1;
    skeleton.joints.row(root) = bone_mass(root) > 0.0 ? Eigen::RowVector3d(centroid.row(root) / bone_mass(root))
                                                      : Eigen::RowVector3d::Zero();
    std::queue<int> queue;
    queue.push(root);
    while (!queue.empty()) {
      const int bone = queue.front();
      queue.pop();
      for (const auto& [next, joint] : tree[static_cast<size_t>(bone)]) {
        if (skeleton.parents[static_cast<size_t>(next)] != -2) continue;
        skeleton.parents[static_cast<size_t>(next)] = bone;
        skeleton.joints.row(next) = joint.transpose();
        skeleton.jointed[static_cast<size_t>(next)].push_back(bone);
        skeleton.jointed[static_cast<size_t>(bone)].push_back(next);
        queue.push(next);
      }
    }
  }
  return skeleton;
}

}  // namespace posekit::detail
