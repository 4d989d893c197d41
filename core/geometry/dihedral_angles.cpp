#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <string>

namespace posekit {
namespace {

int corner_of_edge(const EdgeMap& edges, int face, int edge) {
  for (int corner = 0; corner < 3; ++corner) {
    if (edges.face_edges(face, corner) == edge) return corner;
  }
  return -1;  // unreachable for consistent inputs: the face was listed as incident to the edge
}

Eigen::RowVector3d unnormalized_normal(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                       const Eigen::Ref<const Eigen::MatrixX3i>& faces, int f) {
  const Eigen::RowVector3d a = vertices.row(faces(f, 0));
  return (vertices.row(faces(f, 1)) - a).cross(vertices.row(faces(f, 2)) - a);
}

}  // namespace

Eigen::VectorXd dihedral_angles(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const EdgeMap& edges, const AdjacencyLists& incident_faces) {
  check_face_indices(faces, static_cast<int>(vertices.rows()));
  if (edges.face_edges.rows() != faces.rows()) {
    throw ArgumentError("dihedral_angles: the edge map has " + std::to_string(edges.face_edges.rows()) +
                        " faces but the mesh has " + std::to_string(faces.rows()));
  }
  const auto edge_count = static_cast<int>(edges.edges.rows());
  if (incident_faces.item_count() != edge_count) {
    throw ArgumentError("dihedral_angles: incident_faces lists " + std::to_string(incident_faces.item_count()) +
                        " edges but the edge map has " + std::to_string(edge_count));
  }

  Eigen::VectorXd angles(edge_count);
  for (int e = 0; e < edge_count; ++e) {
    const IndexRange around = incident_faces[e];
    if (around.size() != 2) {
      angles(e) = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const int first = around[0];
    const int second = around[1];
    const int first_corner = corner_of_edge(edges, first, e);
    const int second_corner = corner_of_edge(edges, second, e);
    if (first_corner < 0 || second_corner < 0) {
      throw ArgumentError("dihedral_angles: incident_faces does not match the edge map at edge " +
                          std::to_string(e));
    }
    const int from = faces(first, first_corner);
    const int to = faces(first, (first_corner + 1) % 3);
    const Eigen::RowVector3d direction = (vertices.row(to) - vertices.row(from)).normalized();
    const Eigen::RowVector3d n1 = unnormalized_normal(vertices, faces, first);
    Eigen::RowVector3d n2 = unnormalized_normal(vertices, faces, second);
    // A consistently oriented neighbour runs through the edge from `to` to `from`.
    if (faces(second, second_corner) == from) n2 = -n2;
    // atan2 of sine and cosine terms is accurate near 0 and pi, unlike acos of a dot product.
    angles(e) = std::atan2(n1.cross(n2).dot(direction), n1.dot(n2));
  }
  return angles;
}

Eigen::VectorXd dihedral_angles(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const EdgeMap edges = edge_map(faces);
  return dihedral_angles(vertices, faces, edges, edge_faces(edges));
}

}  // namespace posekit
