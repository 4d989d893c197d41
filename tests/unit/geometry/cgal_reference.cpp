#include "cgal_reference.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <stdexcept>
#include <utility>

namespace posekit::testing {

std::optional<std::vector<int>> cgal_self_intersecting_faces(const Eigen::MatrixX3d& vertices,
                                                             const Eigen::MatrixX3i& faces) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  using SurfaceMesh = CGAL::Surface_mesh<Point>;
  namespace pmp = CGAL::Polygon_mesh_processing;

  std::vector<Point> points;
  points.reserve(static_cast<size_t>(vertices.rows()));
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) points.emplace_back(vertices(v, 0), vertices(v, 1), vertices(v, 2));
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(static_cast<size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    polygons.push_back({static_cast<std::size_t>(faces(f, 0)), static_cast<std::size_t>(faces(f, 1)),
                        static_cast<std::size_t>(faces(f, 2))});
  }
  if (!pmp::is_polygon_soup_a_polygon_mesh(polygons)) return std::nullopt;

  SurfaceMesh mesh;
  pmp::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  // Face indices are compared with posekit's, so the mesh must keep the soup's face order.
  for (const SurfaceMesh::Face_index f : mesh.faces()) {
    std::array<std::size_t, 3> corners{};
    int corner = 0;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      corners[static_cast<size_t>(corner++)] = v.idx();
    }
    std::array<std::size_t, 3> expected = polygons.at(f.idx());
    std::sort(corners.begin(), corners.end());
    std::sort(expected.begin(), expected.end());
    if (corners != expected) throw std::logic_error("CGAL reordered the faces of the polygon soup");
  }
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
  pmp::self_intersections<CGAL::Parallel_if_available_tag>(mesh, std::back_inserter(pairs));

  std::vector<int> result;
  for (const auto& [f, g] : pairs) {
    result.push_back(static_cast<int>(f.idx()));
    result.push_back(static_cast<int>(g.idx()));
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

}  // namespace posekit::testing
