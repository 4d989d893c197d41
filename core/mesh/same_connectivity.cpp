#include <string>

#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"

namespace posekit {
namespace {

std::string face_text(const Eigen::Ref<const Eigen::MatrixX3i>& faces, Eigen::Index f) {
  return "(" + std::to_string(faces(f, 0)) + ", " + std::to_string(faces(f, 1)) + ", " + std::to_string(faces(f, 2)) +
         ")";
}

}  // namespace

void check_same_connectivity(const Mesh& a, const std::string& name_a, const Mesh& b, const std::string& name_b) {
  const std::string rule = ": the poses must share one connectivity";
  if (b.vertices.rows() != a.vertices.rows()) {
    throw InputError(name_b, 0,
                     "has " + std::to_string(b.vertices.rows()) + " vertices but " + name_a + " has " +
                         std::to_string(a.vertices.rows()) + rule);
  }
  if (b.faces.rows() != a.faces.rows()) {
    throw InputError(name_b, 0,
                     "has " + std::to_string(b.faces.rows()) + " faces but " + name_a + " has " +
                         std::to_string(a.faces.rows()) + rule);
  }
  if (b.faces == a.faces) return;
  for (Eigen::Index f = 0; f < a.faces.rows(); ++f) {
    if (b.faces.row(f) != a.faces.row(f)) {
      throw InputError(name_b, 0,
                       "face " + std::to_string(f) + " is " + face_text(b.faces, f) + " but in " + name_a + " it is " +
                           face_text(a.faces, f) + " (zero-based vertex indices)" + rule);
    }
  }
}

}  // namespace posekit
