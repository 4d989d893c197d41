#include <posekit/face_deformation.hpp>
#include <posekit/topology.hpp>

#include <queue>

namespace posekit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Below this angle the principal logarithm is unambiguous and varies continuously between faces.
constexpr double kUnambiguousAngle = 0.9 * kPi;

}  // namespace

// Faces rotated by less than kUnambiguousAngle keep their principal logarithm; the others are reached
// breadth-first from them and take the branch closest to the mean of their already-assigned neighbours.
std::vector<Eigen::Vector3d> consistent_rotation_logs(const std::vector<Eigen::AngleAxisd>& rotations,
                                                      const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const int face_count = static_cast<int>(faces.rows());
  const EdgeMap edges = edge_map(faces);
  const AdjacencyLists faces_of_edge = edge_faces(edges);
  std::vector<Eigen::Vector3d> logs(static_cast<size_t>(face_count));
  std::vector<char> assigned(static_cast<size_t>(face_count), 0);
  std::queue<int> pending;
  const auto principal = [&](int f) {
    const Eigen::AngleAxisd& r = rotations[static_cast<size_t>(f)];
    return Eigen::Vector3d(r.angle() * r.axis());
  };
  const auto assign_from_neighbours = [&](int face) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    int count = 0;
    for (int corner = 0; corner < 3; ++corner) {
      for (int neighbour : faces_of_edge[edges.face_edges(face, corner)]) {
        if (neighbour == face || !assigned[static_cast<size_t>(neighbour)]) continue;
        mean += logs[static_cast<size_t>(neighbour)];
        ++count;
      }
    }
    const Eigen::AngleAxisd& r = rotations[static_cast<size_t>(face)];
    const Eigen::Vector3d first = r.angle() * r.axis();
    const Eigen::Vector3d second = (r.angle() - 2.0 * kPi) * r.axis();
    if (count > 0) mean /= count;
    logs[static_cast<size_t>(face)] =
        count == 0 || (first - mean).squaredNorm() <= (second - mean).squaredNorm() ? first : second;
    assigned[static_cast<size_t>(face)] = 1;
  };
  const auto spread = [&]() {
    while (!pending.empty()) {
      const int face = pending.front();
      pending.pop();
      for (int corner = 0; corner < 3; ++corner) {
        for (int neighbour : faces_of_edge[edges.face_edges(face, corner)]) {
          if (assigned[static_cast<size_t>(neighbour)]) continue;
          assign_from_neighbours(neighbour);
          pending.push(neighbour);
        }
      }
    }
  };
  for (int f = 0; f < face_count; ++f) {
    if (rotations[static_cast<size_t>(f)].angle() < kUnambiguousAngle) {
      logs[static_cast<size_t>(f)] = principal(f);
      assigned[static_cast<size_t>(f)] = 1;
      pending.push(f);
    }
  }
  spread();
  // Components rotated by nearly pi everywhere: seed each with its least rotated face.
  for (int f = 0; f < face_count; ++f) {
    if (assigned[static_cast<size_t>(f)]) continue;
    logs[static_cast<size_t>(f)] = principal(f);
    assigned[static_cast<size_t>(f)] = 1;
    pending.push(f);
    spread();
  }
  return logs;
}

}  // namespace posekit
