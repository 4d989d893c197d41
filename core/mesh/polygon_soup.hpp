// The polygon soup CGAL's readers give (cgal/polygon_soup_io.hpp) as a triangle mesh.
#pragma once

#include <string>

#include "cgal/polygon_soup_io.hpp"
#include "posekit/mesh.hpp"

namespace posekit::detail {

/// The soup as a triangle mesh; throws InputError(file, 0, ...) for a polygon that is not a triangle
/// or an index outside the points (the scans catch both first, this is the last guard).
Mesh mesh_from_soup(const PolygonSoup& soup, const std::string& file);

}  // namespace posekit::detail
