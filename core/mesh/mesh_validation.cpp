#include "posekit/mesh_validation.hpp"

#include "cgal/face_pair_test.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "posekit/error.hpp"

namespace posekit {
namespace {

bool is_finite_row(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, Eigen::Index row) {
  return std::isfinite(vertices(row, 0)) && std::isfinite(vertices(row, 1)) && std::isfinite(vertices(row, 2));
}

std::string plural(int count, const char* singular, const char* plural_form) {
  return std::to_string(count) + " " + (count == 1 ? singular : plural_form);
}

}  // namespace

MeshDefects find_mesh_defects(const Mesh& mesh) {
  const Eigen::Index vertex_count = mesh.vertices.rows();
  MeshDefects defects;
  const detail::FacePairTest exact(mesh.vertices, mesh.faces);
  std::vector<char> referenced(static_cast<std::size_t>(vertex_count), 0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const int a = mesh.faces(f, 0);
    const int b = mesh.faces(f, 1);
    const int c = mesh.faces(f, 2);
    if (a < 0 || b < 0 || c < 0 || a >= vertex_count || b >= vertex_count || c >= vertex_count) continue;
    referenced[static_cast<std::size_t>(a)] = 1;
    referenced[static_cast<std::size_t>(b)] = 1;
    referenced[static_cast<std::size_t>(c)] = 1;
    bool degenerate = a == b || b == c || a == c;
    // The exact predicate cannot take nan or infinity; such a face is an error for validate_mesh anyway.
    if (!degenerate && is_finite_row(mesh.vertices, a) && is_finite_row(mesh.vertices, b) &&
        is_finite_row(mesh.vertices, c)) {
      degenerate = exact.degenerate(static_cast<int>(f));
    }
    if (degenerate) {
      if (defects.degenerate_face_count == 0) defects.first_degenerate_face = static_cast<int>(f);
      ++defects.degenerate_face_count;
    }
  }
  for (std::size_t v = 0; v < referenced.size(); ++v) {
    if (referenced[v] != 0) continue;
    if (defects.unreferenced_vertex_count == 0) defects.first_unreferenced_vertex = static_cast<int>(v);
    ++defects.unreferenced_vertex_count;
  }
  return defects;
}

void validate_mesh(const Mesh& mesh, const std::string& source, std::vector<std::string>* warnings) {
  const Eigen::Index vertex_count = mesh.vertices.rows();
  if (vertex_count == 0) throw InputError(source, 0, "the mesh has no vertices");
  if (mesh.faces.rows() == 0) throw InputError(source, 0, "the mesh has no faces");
  if (!mesh.vertices.allFinite()) {
    for (Eigen::Index v = 0; v < vertex_count; ++v) {
      for (Eigen::Index k = 0; k < 3; ++k) {
        const double value = mesh.vertices(v, k);
        if (!std::isfinite(value)) {
          throw InputError(
              source, 0,
              "vertex " + std::to_string(v) + " has a non-finite coordinate (" + std::to_string(value) + ")");
        }
      }
    }
  }
  if (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= vertex_count) {
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
      for (Eigen::Index k = 0; k < 3; ++k) {
        const int index = mesh.faces(f, k);
        if (index < 0) {
          throw InputError(source, 0,
                           "face " + std::to_string(f) + " uses negative vertex index " + std::to_string(index));
        }
        if (index >= vertex_count) {
          throw InputError(source, 0,
                           "face " + std::to_string(f) + " uses vertex index " + std::to_string(index) +
                               ", out of range: the mesh has " + std::to_string(vertex_count) + " vertices");
        }
      }
    }
  }
  if (warnings == nullptr) return;
  const MeshDefects defects = find_mesh_defects(mesh);
  if (defects.unreferenced_vertex_count > 0) {
    warnings->push_back(source + ": " +
                        plural(defects.unreferenced_vertex_count, "unreferenced vertex", "unreferenced vertices") +
                        " (used by no face; first: vertex " + std::to_string(defects.first_unreferenced_vertex) + ")");
  }
  if (defects.degenerate_face_count > 0) {
    warnings->push_back(source + ": " + plural(defects.degenerate_face_count, "degenerate face", "degenerate faces") +
                        " (repeated vertex or zero area; first: face " + std::to_string(defects.first_degenerate_face) +
                        ")");
  }
}

}  // namespace posekit
