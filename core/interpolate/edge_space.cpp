#include <posekit/edge_space.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <string>

namespace posekit {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Twice the area against the longest edge squared: below this a face's normal is noise.
constexpr double kDegenerateRatio = 1e-10;

}  // namespace

double wrap_angle(double angle) {
  if (angle >= -kPi && angle <= kPi) return angle;
  return angle - 2.0 * kPi * std::round(angle / (2.0 * kPi));
}

EdgeSpaceCoordinates edge_space_coordinates(const PoseSet& poses, const EdgeMap& edges,
                                            const AdjacencyLists& incident_faces) {
  const int pose_count = poses.pose_count();
  if (pose_count == 0) throw ArgumentError("edge_space_coordinates: the pose set has no pose");
  const Eigen::MatrixX3i& faces = poses.faces();
  const int edge_count = static_cast<int>(edges.edges.rows());
  if (edges.face_edges.rows() != faces.rows() || incident_faces.item_count() != edge_count) {
    throw ArgumentError("edge_space_coordinates: the edge maps do not belong to the pose set's " +
                        std::to_string(faces.rows()) + " faces");
  }
  const int face_count = static_cast<int>(faces.rows());
  EdgeSpaceCoordinates result;
  result.lengths.resize(edge_count, pose_count);
  result.angles.resize(edge_count, pose_count);
  result.degenerate_face.assign(static_cast<size_t>(face_count), 0);
  tbb::parallel_for(0, pose_count, [&](int k) {
    result.lengths.col(k) = edge_lengths(poses.pose(k), edges.edges);
    result.angles.col(k) = dihedral_angles(poses.pose(k), faces, edges, incident_faces);
  });
  for (int k = 0; k < pose_count; ++k) {
    const Eigen::MatrixX3d& x = poses.pose(k);
    for (int f = 0; f < face_count; ++f) {
      const Eigen::RowVector3d a = x.row(faces(f, 0));
      const Eigen::RowVector3d b = x.row(faces(f, 1));
      const Eigen::RowVector3d c = x.row(faces(f, 2));
      const double twice_area = (b - a).cross(c - a).norm();
      const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
      if (!(twice_area > kDegenerateRatio * longest)) result.degenerate_face[static_cast<size_t>(f)] = 1;
    }
  }
  result.hinge.assign(static_cast<size_t>(edge_count), 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int e = 0; e < edge_count; ++e) {
    const IndexRange around = incident_faces[e];
    bool hinge = around.size() == 2 && std::isfinite(result.angles(e, 0));
    for (const int f : around) hinge = hinge && !result.degenerate_face[static_cast<size_t>(f)];
    result.hinge[static_cast<size_t>(e)] = hinge ? 1 : 0;
    if (!hinge) {
      result.angles.row(e).setConstant(nan);
      continue;
    }
    const double first = result.angles(e, 0);
    for (int k = 1; k < pose_count; ++k) {
      const double angle = result.angles(e, k);
      result.angles(e, k) = angle + 2.0 * kPi * std::round((first - angle) / (2.0 * kPi));
    }
  }
  return result;
}

}  // namespace posekit
