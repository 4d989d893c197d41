#include "mesh/polygon_soup.hpp"

#include <array>
#include <climits>

#include "posekit/error.hpp"

namespace posekit::detail {

Mesh mesh_from_soup(const PolygonSoup& soup, const std::string& file) {
  const std::size_t vertex_count = soup.points.size();
  if (vertex_count > static_cast<std::size_t>(INT_MAX) || soup.polygons.size() > static_cast<std::size_t>(INT_MAX)) {
    throw InputError(file, 0, "the mesh has more than " + std::to_string(INT_MAX) + " vertices or faces");
  }
  Mesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertex_count), 3);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const std::array<double, 3>& point = soup.points[v];
    const auto row = static_cast<Eigen::Index>(v);
    mesh.vertices(row, 0) = point[0];
    mesh.vertices(row, 1) = point[1];
    mesh.vertices(row, 2) = point[2];
  }
  mesh.faces.resize(static_cast<Eigen::Index>(soup.polygons.size()), 3);
  for (std::size_t f = 0; f < soup.polygons.size(); ++f) {
    const std::vector<std::size_t>& polygon = soup.polygons[f];
    if (polygon.size() != 3) {
      throw InputError(file, 0,
                       "face " + std::to_string(f) + " has " + std::to_string(polygon.size()) +
                           " vertices; only triangles are supported");
    }
    for (int corner = 0; corner < 3; ++corner) {
      const std::size_t index = polygon[static_cast<std::size_t>(corner)];
      if (index >= vertex_count) {
        throw InputError(file, 0,
                         "face " + std::to_string(f) + " uses vertex index " + std::to_string(index) +
                             ", out of range: the file has " + std::to_string(vertex_count) + " vertices");
      }
      mesh.faces(static_cast<Eigen::Index>(f), corner) = static_cast<int>(index);
    }
  }
  return mesh;
}

}  // namespace posekit::detail
