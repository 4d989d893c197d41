// Checks of a triangle mesh that do not depend on where it came from: errors that make it unusable and
// defects worth a warning.
#pragma once

#include <string>
#include <vector>

#include "posekit/mesh.hpp"

namespace posekit {

/// Defects that leave a mesh usable. Indices are zero-based; -1 when the count is 0.
struct MeshDefects {
  int unreferenced_vertex_count = 0;  ///< vertices that no face uses
  int first_unreferenced_vertex = -1;
  int degenerate_face_count = 0;  ///< faces with a repeated vertex or exactly zero area
  int first_degenerate_face = -1;
};

/// Counts the defects of `mesh` (#V by 3 vertices, #F by 3 faces). Zero area is decided exactly
/// (CGAL's collinearity predicate). Faces with an index outside [0, #V) are skipped, not counted.
MeshDefects find_mesh_defects(const Mesh& mesh);

/// Checks `mesh`, read from `source` (the file name used in messages). Throws InputError(source, 0, ...)
/// if it has no vertices or no faces, a non-finite coordinate, or a face index outside [0, #V).
/// Otherwise appends one line per kind of defect to `warnings` (when given), each naming `source`,
/// the count and the first vertex or face.
void validate_mesh(const Mesh& mesh, const std::string& source, std::vector<std::string>* warnings = nullptr);

}  // namespace posekit
