// The polygon soup CGAL's readers and writers exchange, and its conversion to and from a Mesh.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "posekit/mesh.hpp"

namespace posekit::detail {

using SoupKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SoupPoint = SoupKernel::Point_3;

/// Points and polygons in file order, as CGAL::IO reads them.
struct PolygonSoup {
  std::vector<SoupPoint> points;
  std::vector<std::vector<std::size_t>> polygons;
};

/// The soup as a triangle mesh; throws InputError(file, 0, ...) for a polygon that is not a triangle
/// or an index outside the points (the scans catch both first, this is the last guard).
Mesh mesh_from_soup(const PolygonSoup& soup, const std::string& file);

/// #V points and #F triangles of `mesh`, for CGAL's writers (indices are assumed valid).
void soup_from_mesh(const Mesh& mesh, std::vector<SoupPoint>& points,
                    std::vector<std::array<std::size_t, 3>>& triangles);

}  // namespace posekit::detail
