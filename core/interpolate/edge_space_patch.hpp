// A set of faces of the mesh with its own vertex, face and edge numbering: the piece of edge space
// that one reconstruction works on (one joint, or the whole mesh for the edge-space baseline).
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::interpolation {

/// An edge of the patch with a dihedral angle: both its faces are in the patch and it is a hinge of
/// the mesh. The first face (the one with the lower index) runs through the edge from a to b; c is the
/// third corner of the first face, d of the second. All indices are local to the patch.
struct Hinge {
  int edge = -1;
  int first = -1;
  int second = -1;
  int first_side = -1;   ///< side (corner k -> k + 1) of the first face that is this edge
  int second_side = -1;  ///< the same in the second face
  int a = -1, b = -1, c = -1, d = -1;
  bool consistent = true;  ///< the second face runs from b to a (the two faces are oriented alike)
};

struct EdgeSpacePatch {
  std::vector<int> vertices;      ///< local vertex -> mesh vertex
  std::vector<int> mesh_faces;    ///< local face -> mesh face (ascending)
  Eigen::MatrixX3i faces;         ///< local corners of each local face
  Eigen::MatrixX2i edges;         ///< local vertex pairs of the local edges
  std::vector<int> mesh_edges;    ///< local edge -> mesh edge
  std::vector<int> mesh_hinges;   ///< hinge -> mesh edge
  Eigen::MatrixX3i face_edges;    ///< local edge of side k (corner k -> k + 1) of each local face
  std::vector<Hinge> hinges;

  int vertex_count() const { return static_cast<int>(vertices.size()); }
  int face_count() const { return static_cast<int>(faces.rows()); }
  int edge_count() const { return static_cast<int>(edges.rows()); }
  int hinge_count() const { return static_cast<int>(hinges.size()); }
};

/// The patch of the ascending mesh faces `patch_faces` of `faces` (#F by 3, `vertex_count` vertices),
/// with `edges` = edge_map(faces), `incident_faces` = edge_faces(edges) and the #E mesh `hinge` flags.
EdgeSpacePatch make_edge_space_patch(const std::vector<int>& patch_faces,
                                     const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                     int vertex_count, const EdgeMap& edges, const AdjacencyLists& incident_faces,
                                     const std::vector<char>& hinge);

/// Signed dihedral angle of `hinge` (the convention of dihedral_angles) for the local positions `x`.
double hinge_angle(const Hinge& hinge, const Eigen::Ref<const Eigen::MatrixX3d>& x);

/// Gradient of hinge_angle with respect to the positions of a, b, c and d (rows 0 to 3).
Eigen::Matrix<double, 4, 3> hinge_angle_gradient(const Hinge& hinge, const Eigen::Ref<const Eigen::MatrixX3d>& x);

}  // namespace posekit::interpolation
