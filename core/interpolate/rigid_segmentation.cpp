#include <posekit/error.hpp>
#include <posekit/face_deformation.hpp>
#include <posekit/rigid_motion.hpp>
#include <posekit/rigid_segmentation.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <queue>
#include <string>
#include <vector>

namespace posekit {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSmallestPart = 10;

// Per face and pose k = 1 .. K-1, the rotation from pose 0 as a unit quaternion (4 doubles).
class FaceRotations {
 public:
  FaceRotations(const PoseSet& poses) : pose_pairs_(poses.pose_count() - 1) {
    const int face_count = static_cast<int>(poses.faces().rows());
    data_.resize(static_cast<size_t>(face_count) * static_cast<size_t>(pose_pairs_) * 4);
    for (int k = 1; k < poses.pose_count(); ++k) {
      const std::vector<Eigen::Matrix3d> gradients =
          face_deformation_gradients(poses.pose(0), poses.pose(k), poses.faces());
      tbb::parallel_for(0, face_count, [&](int f) {
        const Eigen::Quaterniond q(polar_decomposition(gradients[static_cast<size_t>(f)]).rotation);
        double* slot = at(f, k - 1);
        slot[0] = q.w();
        slot[1] = q.x();
        slot[2] = q.y();
        slot[3] = q.z();
      });
    }
  }

  // Cosine of half the largest angle, over all poses, between the rotations of faces f and g.
  double similarity(int f, int g) const {
    double lowest = 1.0;
    for (int k = 0; k < pose_pairs_; ++k) {
      const double* a = at(f, k);
      const double* b = at(g, k);
      lowest = std::min(lowest, std::abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]));
    }
    return lowest;
  }

 private:
  double* at(int f, int k) { return data_.data() + (static_cast<size_t>(f) * pose_pairs_ + k) * 4; }
  const double* at(int f, int k) const { return data_.data() + (static_cast<size_t>(f) * pose_pairs_ + k) * 4; }
  int pose_pairs_;
  std::vector<double> data_;
};

// Faces sharing an edge with each face (each listed once).
std::vector<std::vector<int>> face_neighbours(const EdgeMap& edges, const AdjacencyLists& incident_faces) {
  const int face_count = static_cast<int>(edges.face_edges.rows());
  std::vector<std::vector<int>> neighbours(static_cast<size_t>(face_count));
  for (int f = 0; f < face_count; ++f) {
    std::vector<int>& list = neighbours[static_cast<size_t>(f)];
    for (int corner = 0; corner < 3; ++corner) {
      for (const int g : incident_faces[edges.face_edges(f, corner)]) {
        if (g != f) list.push_back(g);
      }
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

int find_root(std::vector<int>& parent, int item) {
  while (parent[static_cast<size_t>(item)] != item) {
    parent[static_cast<size_t>(item)] = parent[static_cast<size_t>(parent[static_cast<size_t>(item)])];
    item = parent[static_cast<size_t>(item)];
  }
  return item;
}

// Merges every region smaller than `smallest` into the neighbouring region with which it shares the
// most edges, smallest regions first; a region without neighbours stays.
Eigen::VectorXi merge_small_regions(Eigen::VectorXi labels, int region_count, int smallest,
                                    const std::vector<std::vector<int>>& neighbours) {
  std::vector<int> size(static_cast<size_t>(region_count), 0);
  for (Eigen::Index f = 0; f < labels.size(); ++f) ++size[static_cast<size_t>(labels(f))];
  std::vector<std::map<int, int>> shared(static_cast<size_t>(region_count));
  for (Eigen::Index f = 0; f < labels.size(); ++f) {
    for (const int g : neighbours[static_cast<size_t>(f)]) {
      if (labels(g) != labels(f)) ++shared[static_cast<size_t>(labels(f))][labels(g)];
    }
  }
  std::vector<int> parent(static_cast<size_t>(region_count));
  std::iota(parent.begin(), parent.end(), 0);
  using Entry = std::pair<int, int>;  // size, region
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> pending;
  for (int r = 0; r < region_count; ++r) {
    if (size[static_cast<size_t>(r)] < smallest) pending.emplace(size[static_cast<size_t>(r)], r);
  }
  while (!pending.empty()) {
    const auto [queued_size, region] = pending.top();
    pending.pop();
    if (find_root(parent, region) != region || size[static_cast<size_t>(region)] != queued_size) continue;
    if (queued_size >= smallest) continue;
    // Neighbour counts are kept per root; entries of merged regions are folded in here.
    std::map<int, int> counts;
    for (const auto& [other, count] : shared[static_cast<size_t>(region)]) {
      const int root = find_root(parent, other);
      if (root != region) counts[root] += count;
    }
    shared[static_cast<size_t>(region)] = counts;
    if (counts.empty()) continue;
    int best = -1;
    int best_count = -1;
    for (const auto& [other, count] : counts) {
      if (count > best_count) {
        best = other;
        best_count = count;
      }
    }
    parent[static_cast<size_t>(region)] = best;
    size[static_cast<size_t>(best)] += size[static_cast<size_t>(region)];
    for (const auto& [other, count] : counts) {
      if (other != best) shared[static_cast<size_t>(best)][other] += count;
    }
    if (size[static_cast<size_t>(best)] < smallest) pending.emplace(size[static_cast<size_t>(best)], best);
  }
  for (Eigen::Index f = 0; f < labels.size(); ++f) labels(f) = find_root(parent, labels(f));
  return labels;
}

}  // namespace

Eigen::VectorXi connected_parts(const Eigen::VectorXi& face_labels, const EdgeMap& edges,
                                const AdjacencyLists& incident_faces) {
  const auto face_count = static_cast<int>(edges.face_edges.rows());
  if (face_labels.size() != face_count) {
    throw ArgumentError("connected_parts: " + std::to_string(face_labels.size()) + " labels for " +
                        std::to_string(face_count) + " faces");
  }
  Eigen::VectorXi parts = Eigen::VectorXi::Constant(face_count, -1);
  int next = 0;
  std::vector<int> stack;
  for (int start = 0; start < face_count; ++start) {
    if (parts(start) >= 0) continue;
    parts(start) = next;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int corner = 0; corner < 3; ++corner) {
        for (const int g : incident_faces[edges.face_edges(f, corner)]) {
          if (parts(g) >= 0 || face_labels(g) != face_labels(f)) continue;
          parts(g) = next;
          stack.push_back(g);
        }
      }
    }
    ++next;
  }
  return parts;
}

Eigen::VectorXi face_labels_from_vertex_labels(const Eigen::VectorXi& vertex_labels,
                                               const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  check_face_indices(faces, static_cast<int>(vertex_labels.size()));
  Eigen::VectorXi labels(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const int a = vertex_labels(faces(f, 0));
    const int b = vertex_labels(faces(f, 1));
    const int c = vertex_labels(faces(f, 2));
    labels(f) = (a == b || a == c) ? a : (b == c ? b : std::min({a, b, c}));
  }
  return labels;
}

Eigen::VectorXi segment_rigid_parts(const PoseSet& poses, const SegmentationOptions& options) {
  if (poses.pose_count() < 2) {
    throw ArgumentError("segment_rigid_parts: needs at least two poses, got " + std::to_string(poses.pose_count()));
  }
  if (!(options.rigidity_angle_degrees > 0.0 && options.rigidity_angle_degrees < 180.0)) {
    throw ArgumentError("SegmentationOptions::rigidity_angle_degrees must lie in (0, 180)");
  }
  if (!(options.min_part_fraction >= 0.0 && options.min_part_fraction < 1.0)) {
    throw ArgumentError("SegmentationOptions::min_part_fraction must lie in [0, 1)");
  }
  const Eigen::MatrixX3i& faces = poses.faces();
  const int face_count = static_cast<int>(faces.rows());
  const EdgeMap edges = edge_map(faces);
  const AdjacencyLists incident_faces = edge_faces(edges);
  const std::vector<std::vector<int>> neighbours = face_neighbours(edges, incident_faces);
  const FaceRotations rotations(poses);

  // Seeds in order of rigidity: a face whose neighbours all turn with it comes first.
  std::vector<double> rigidity(static_cast<size_t>(face_count), 1.0);
  tbb::parallel_for(0, face_count, [&](int f) {
    double lowest = 1.0;
    for (const int g : neighbours[static_cast<size_t>(f)]) lowest = std::min(lowest, rotations.similarity(f, g));
    rigidity[static_cast<size_t>(f)] = lowest;
  });
  std::vector<int> order(static_cast<size_t>(face_count));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return rigidity[static_cast<size_t>(a)] > rigidity[static_cast<size_t>(b)];
  });

  const double threshold = std::cos(0.5 * options.rigidity_angle_degrees * kPi / 180.0);
  Eigen::VectorXi labels = Eigen::VectorXi::Constant(face_count, -1);
  int region_count = 0;
  std::vector<int> queue;
  for (const int seed : order) {
    if (labels(seed) >= 0) continue;
    labels(seed) = region_count;
    queue.assign(1, seed);
    for (size_t next = 0; next < queue.size(); ++next) {
      for (const int g : neighbours[static_cast<size_t>(queue[next])]) {
        if (labels(g) >= 0 || rotations.similarity(seed, g) < threshold) continue;
        labels(g) = region_count;
        queue.push_back(g);
      }
    }
    ++region_count;
  }
  const int smallest =
      std::max(kSmallestPart, static_cast<int>(std::ceil(options.min_part_fraction * static_cast<double>(face_count))));
  labels = merge_small_regions(labels, region_count, smallest, neighbours);
  return connected_parts(labels, edges, incident_faces);
}

}  // namespace posekit
