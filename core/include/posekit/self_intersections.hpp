// Self-intersection detection with exact predicates, parallel over candidate face pairs.
//
// Two faces intersect when their triangles share a point other than a vertex or an edge that both
// faces use (by vertex index). This matches CGAL::Polygon_mesh_processing::self_intersections:
//  - faces sharing an edge intersect only when the four points are coplanar and the two triangles
//    lie on the same side of the edge (they fold onto each other);
//  - faces sharing exactly one vertex intersect when the edge of either face opposite the shared
//    vertex meets the other triangle;
//  - faces using the same three vertices intersect (they coincide);
//  - a degenerate face (its three corners collinear or repeated) is reported as intersecting by
//    itself and is not tested against other faces.
// On a non-manifold edge every pair of its faces gets the shared-edge test, which is what "truly
// overlap" means there; CGAL cannot represent such a face list as a polygon mesh without splitting it.
#pragma once

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace posekit {

/// Intersecting face pairs (f, g) with f < g, sorted, of the #V by 3 `vertices` and #F by 3 `faces`;
/// a degenerate face f appears once as (f, f). Throws ArgumentError on a face index outside [0, #V)
/// or a coordinate that is not finite.
std::vector<std::pair<int, int>> self_intersecting_face_pairs(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                                              const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// Sorted, distinct faces named in `pairs` (as from self_intersecting_face_pairs()).
std::vector<int> faces_in_pairs(const std::vector<std::pair<int, int>>& pairs);

/// Sorted indices of the faces that intersect some other face (or are degenerate), i.e. the distinct
/// faces of self_intersecting_face_pairs(). `vertices` #V by 3, `faces` #F by 3.
std::vector<int> self_intersecting_faces(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// Faces listed in `mesh_faces` but not in `reference_faces` (both face index lists of poses sharing
/// one connectivity, in any order): the intersections a pose has that its reference does not. Sorted,
/// distinct.
std::vector<int> new_intersecting_faces(const std::vector<int>& mesh_faces, const std::vector<int>& reference_faces);

}  // namespace posekit
