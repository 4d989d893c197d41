#include "interpolate/edge_space_patch.hpp"

#include <posekit/error.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace posekit::interpolation {

EdgeSpacePatch make_edge_space_patch(const std::vector<int>& patch_faces,
                                     const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                     int vertex_count, const EdgeMap& edges, const AdjacencyLists& incident_faces,
                                     const std::vector<char>& hinge) {
  EdgeSpacePatch patch;
  patch.mesh_faces = patch_faces;
  if (!std::is_sorted(patch.mesh_faces.begin(), patch.mesh_faces.end())) {
    throw ArgumentError("make_edge_space_patch: faces must be ascending");
  }
  const int face_count = static_cast<int>(patch_faces.size());
  std::vector<int> local_vertex(static_cast<size_t>(vertex_count), -1);
  std::vector<int> local_face(static_cast<size_t>(faces.rows()), -1);
  for (int f = 0; f < face_count; ++f) {
    local_face[static_cast<size_t>(patch_faces[static_cast<size_t>(f)])] = f;
    for (int corner = 0; corner < 3; ++corner) patch.vertices.push_back(faces(patch_faces[static_cast<size_t>(f)], corner));
  }
  std::sort(patch.vertices.begin(), patch.vertices.end());
  patch.vertices.erase(std::unique(patch.vertices.begin(), patch.vertices.end()), patch.vertices.end());
  for (size_t v = 0; v < patch.vertices.size(); ++v) local_vertex[static_cast<size_t>(patch.vertices[v])] = static_cast<int>(v);

  for (int f = 0; f < face_count; ++f) {
    for (int side = 0; side < 3; ++side) patch.mesh_edges.push_back(edges.face_edges(patch_faces[static_cast<size_t>(f)], side));
  }
  std::sort(patch.mesh_edges.begin(), patch.mesh_edges.end());
  patch.mesh_edges.erase(std::unique(patch.mesh_edges.begin(), patch.mesh_edges.end()), patch.mesh_edges.end());
  const int edge_count = static_cast<int>(patch.mesh_edges.size());
  patch.edges.resize(edge_count, 2);
  for (int e = 0; e < edge_count; ++e) {
    for (int end = 0; end < 2; ++end) {
      patch.edges(e, end) = local_vertex[static_cast<size_t>(edges.edges(patch.mesh_edges[static_cast<size_t>(e)], end))];
    }
  }
  const auto local_edge = [&](int mesh_edge) {
    return static_cast<int>(std::lower_bound(patch.mesh_edges.begin(), patch.mesh_edges.end(), mesh_edge) -
                            patch.mesh_edges.begin());
  };
  patch.faces.resize(face_count, 3);
  patch.face_edges.resize(face_count, 3);
  for (int f = 0; f < face_count; ++f) {
    const int mesh_face = patch_faces[static_cast<size_t>(f)];
    for (int corner = 0; corner < 3; ++corner) {
      patch.faces(f, corner) = local_vertex[static_cast<size_t>(faces(mesh_face, corner))];
      patch.face_edges(f, corner) = local_edge(edges.face_edges(mesh_face, corner));
    }
  }
  for (int e = 0; e < edge_count; ++e) {
    const int mesh_edge = patch.mesh_edges[static_cast<size_t>(e)];
    if (!hinge[static_cast<size_t>(mesh_edge)]) continue;
    const IndexRange around = incident_faces[mesh_edge];
    if (around.size() != 2) continue;
    const int first = local_face[static_cast<size_t>(around[0])];
    const int second = local_face[static_cast<size_t>(around[1])];
    if (first < 0 || second < 0) continue;
    Hinge h;
    h.edge = e;
    h.first = first;
    h.second = second;
    for (int side = 0; side < 3; ++side) {
      if (patch.face_edges(first, side) == e) h.first_side = side;
      if (patch.face_edges(second, side) == e) h.second_side = side;
    }
    h.a = patch.faces(first, h.first_side);
    h.b = patch.faces(first, (h.first_side + 1) % 3);
    h.c = patch.faces(first, (h.first_side + 2) % 3);
    h.consistent = patch.faces(second, h.second_side) == h.b;
    h.d = patch.faces(second, (h.second_side + 2) % 3);
    patch.hinges.push_back(h);
    patch.mesh_hinges.push_back(mesh_edge);
  }
  return patch;
}

double hinge_angle(const Hinge& h, const Eigen::Ref<const Eigen::MatrixX3d>& x) {
  const Eigen::Vector3d a = x.row(h.a);
  const Eigen::Vector3d b = x.row(h.b);
  const Eigen::Vector3d c = x.row(h.c);
  const Eigen::Vector3d d = x.row(h.d);
  // Normals of (a, b, c) and (b, a, d): the second face's normal as if it were oriented like the first.
  const Eigen::Vector3d n1 = (b - a).cross(c - a);
  const Eigen::Vector3d n2 = (a - b).cross(d - b);
  const Eigen::Vector3d direction = (b - a).normalized();
  return std::atan2(n1.cross(n2).dot(direction), n1.dot(n2));
}

Eigen::Matrix<double, 4, 3> hinge_angle_gradient(const Hinge& h, const Eigen::Ref<const Eigen::MatrixX3d>& x) {
  const Eigen::Vector3d a = x.row(h.a);
  const Eigen::Vector3d b = x.row(h.b);
  const Eigen::Vector3d c = x.row(h.c);
  const Eigen::Vector3d d = x.row(h.d);
  const Eigen::Vector3d e = b - a;
  const double length = e.norm();
  Eigen::Matrix<double, 4, 3> gradient = Eigen::Matrix<double, 4, 3>::Zero();
  if (!(length > 0.0)) return gradient;
  const Eigen::Vector3d n1 = e.cross(c - a);
  const Eigen::Vector3d n2 = (a - b).cross(d - b);
  const double s1 = n1.squaredNorm();
  const double s2 = n2.squaredNorm();
  if (!(s1 > 0.0) || !(s2 > 0.0)) return gradient;
  const Eigen::Vector3d m1 = n1 / s1;  // normal over twice the area, per unit of height
  const Eigen::Vector3d m2 = n2 / s2;
  const Eigen::Vector3d unit = e / length;
  // Moving an opposite corner along its face normal turns that face about the edge by the distance over
  // the corner's height; the edge's ends share the opposite effect by where the corners project.
  gradient.row(2) = -length * m1;
  gradient.row(3) = -length * m2;
  gradient.row(0) = -((c - b).dot(unit) * m1 + (d - b).dot(unit) * m2);
  gradient.row(1) = (c - a).dot(unit) * m1 + (d - a).dot(unit) * m2;
  return gradient;
}

}  // namespace posekit::interpolation
