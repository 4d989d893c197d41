#include "cgal/polygon_soup_io.hpp"

#include "cgal/kernel.hpp"

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>

#include <limits>

namespace posekit::detail {
namespace {

// Reads with `read` into CGAL's points, then hands them over as plain coordinates.
template <typename Read>
bool read_into(PolygonSoup& soup, Read read) {
  std::vector<ExactPoint> points;
  const bool ok = read(points);
  soup.points.clear();
  soup.points.reserve(points.size());
  for (const ExactPoint& point : points) soup.points.push_back({point.x(), point.y(), point.z()});
  return ok;
}

struct CgalSoup {
  std::vector<ExactPoint> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

CgalSoup cgal_soup(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  CgalSoup soup;
  soup.points.reserve(static_cast<std::size_t>(vertices.rows()));
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) soup.points.push_back(exact_point(vertices, v));
  soup.triangles.reserve(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    soup.triangles.push_back({static_cast<std::size_t>(faces(f, 0)), static_cast<std::size_t>(faces(f, 1)),
                              static_cast<std::size_t>(faces(f, 2))});
  }
  return soup;
}

// max_digits10 significant digits make the decimal text read back as the same double.
auto full_precision() { return CGAL::parameters::stream_precision(std::numeric_limits<double>::max_digits10); }

}  // namespace

bool read_obj_soup(std::istream& stream, PolygonSoup& soup) {
  return read_into(soup, [&](std::vector<ExactPoint>& points) {
    return CGAL::IO::read_OBJ(stream, points, soup.polygons, CGAL::parameters::verbose(false));
  });
}

bool read_off_soup(std::istream& stream, PolygonSoup& soup) {
  return read_into(soup, [&](std::vector<ExactPoint>& points) { return CGAL::IO::read_OFF(stream, points, soup.polygons); });
}

bool read_ply_soup(std::istream& stream, PolygonSoup& soup) {
  return read_into(soup, [&](std::vector<ExactPoint>& points) {
    return CGAL::IO::read_PLY(stream, points, soup.polygons, CGAL::parameters::verbose(false));
  });
}

bool write_obj_soup(std::ostream& stream, const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const CgalSoup soup = cgal_soup(vertices, faces);
  return CGAL::IO::write_OBJ(stream, soup.points, soup.triangles, full_precision());
}

bool write_off_soup(std::ostream& stream, const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const CgalSoup soup = cgal_soup(vertices, faces);
  return CGAL::IO::write_OFF(stream, soup.points, soup.triangles, full_precision());
}

bool write_ply_soup(std::ostream& stream, const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const CgalSoup soup = cgal_soup(vertices, faces);
  CGAL::IO::set_mode(stream, CGAL::IO::BINARY);
  return CGAL::IO::write_PLY(stream, soup.points, soup.triangles, full_precision());
}

}  // namespace posekit::detail
