// The components of the mixed shape space: joints, strips of triangles around the boundaries between
// parts, and rigid pieces, the parts shrunk so that each overlaps its joints by one strip.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::interpolation {

/// A set of faces and the vertices they use, both as ascending global indices.
struct MeshComponent {
  std::vector<int> faces;
  std::vector<int> vertices;
};

struct JointLayout {
  std::vector<MeshComponent> rigid_pieces;
  std::vector<MeshComponent> joints;
  /// #F strip index of each face: 1 for faces touching a part boundary, r + 1 for faces sharing a
  /// vertex with strip r; 0 for faces beyond strip joint_width + 1 (or in a part without boundary).
  Eigen::VectorXi face_strip;
  int joint_face_count = 0;
};

/// Joints are the faces in strips 1 .. `joint_width` (>= 1), split into edge-connected components;
/// rigid pieces are, per part of `face_parts` (#F ids), its faces in strip `joint_width` or beyond (or
/// without strip), split into edge-connected components. Every face lies in a joint or a rigid piece;
/// the faces of strip `joint_width` in both. `edges` = edge_map(faces), `incident_faces` =
/// edge_faces(edges), `neighbours` = vertex_neighbours(faces, #V).
JointLayout build_joint_layout(const Eigen::Ref<const Eigen::MatrixX3i>& faces, const Eigen::VectorXi& face_parts,
                               const EdgeMap& edges,
                               const AdjacencyLists& incident_faces, const AdjacencyLists& neighbours, int joint_width);

}  // namespace posekit::interpolation
