// write_mesh: CGAL's writers format the mesh in memory, then the bytes are written atomically.
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <posekit/atomic_file.hpp>
#include "mesh/polygon_soup.hpp"
#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"

namespace posekit {
namespace {

// A mesh that could not be read back is refused before anything is written.
void check_writable(const Mesh& mesh, const std::string& name) {
  const Eigen::Index vertex_count = mesh.vertices.rows();
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    for (Eigen::Index k = 0; k < 3; ++k) {
      const int index = mesh.faces(f, k);
      if (index < 0 || index >= vertex_count) {
        throw ArgumentError("write_mesh(" + name + "): face " + std::to_string(f) + " uses vertex index " +
                            std::to_string(index) + ", outside the " + std::to_string(vertex_count) + " vertices");
      }
    }
  }
  if (!mesh.vertices.allFinite()) {
    throw ArgumentError("write_mesh(" + name + "): the mesh has a non-finite coordinate");
  }
}

}  // namespace

void write_mesh(const std::filesystem::path& file, const Mesh& mesh) {
  const std::string name = file.string();
  const MeshFormat format = mesh_format_from_extension(file);
  check_writable(mesh, name);

  std::vector<detail::SoupPoint> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  detail::soup_from_mesh(mesh, points, triangles);

  // max_digits10 significant digits make the decimal text read back as the same double.
  const auto precision = CGAL::parameters::stream_precision(std::numeric_limits<double>::max_digits10);
  std::ostringstream stream(std::ios::out | std::ios::binary);
  bool ok = false;
  switch (format) {
    case MeshFormat::obj:
      ok = CGAL::IO::write_OBJ(stream, points, triangles, precision);
      break;
    case MeshFormat::off:
      ok = CGAL::IO::write_OFF(stream, points, triangles, precision);
      break;
    case MeshFormat::ply:
      CGAL::IO::set_mode(stream, CGAL::IO::BINARY);
      ok = CGAL::IO::write_PLY(stream, points, triangles, precision);
      break;
  }
  if (!ok) throw InputError(name, 0, "cannot format the mesh for writing");
  write_file_atomically(file, stream.str());
}

}  // namespace posekit
