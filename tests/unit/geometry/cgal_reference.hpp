// Self-intersections as CGAL::Polygon_mesh_processing reports them, the yardstick for posekit's own.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace posekit::testing {

/// Sorted faces of the #V by 3 `vertices` and #F by 3 `faces` that CGAL::Polygon_mesh_processing::
/// self_intersections reports (degenerate faces included, as it does), computed on a
/// CGAL::Surface_mesh whose face i is face i of `faces`. nullopt when the face list is not a polygon
/// mesh (non-manifold or inconsistently oriented), which CGAL's function cannot take.
std::optional<std::vector<int>> cgal_self_intersecting_faces(const Eigen::MatrixX3d& vertices,
                                                             const Eigen::MatrixX3i& faces);

}  // namespace posekit::testing
