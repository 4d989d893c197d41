// CGAL's polygon-soup readers and writers behind plain types, so that the mesh layer reads and writes
// files without including CGAL.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <istream>
#include <ostream>
#include <vector>

namespace posekit::detail {

/// Points and polygons in file order, as CGAL::IO reads them.
struct PolygonSoup {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> polygons;
};

/// CGAL's reader of each format on `stream` (quiet): false where it reports a failure; it may also
/// throw. CGAL trusts its input, so callers check the text first (mesh/mesh_file_scan.hpp).
bool read_obj_soup(std::istream& stream, PolygonSoup& soup);
bool read_off_soup(std::istream& stream, PolygonSoup& soup);
bool read_ply_soup(std::istream& stream, PolygonSoup& soup);

/// CGAL's writer of each format: the #V by 3 `vertices` and #F by 3 `faces` (valid indices), every
/// coordinate with enough digits to read back as the same double; PLY is binary. False on failure.
bool write_obj_soup(std::ostream& stream, const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces);
bool write_off_soup(std::ostream& stream, const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces);
bool write_ply_soup(std::ostream& stream, const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces);

}  // namespace posekit::detail
