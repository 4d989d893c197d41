// write_mesh: CGAL's writers format the mesh in memory, then the bytes are written atomically.
#include <sstream>
#include <string>

#include <posekit/atomic_file.hpp>
#include "cgal/polygon_soup_io.hpp"
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

  std::ostringstream stream(std::ios::out | std::ios::binary);
  bool ok = false;
  switch (format) {
    case MeshFormat::obj:
      ok = detail::write_obj_soup(stream, mesh.vertices, mesh.faces);
      break;
    case MeshFormat::off:
      ok = detail::write_off_soup(stream, mesh.vertices, mesh.faces);
      break;
    case MeshFormat::ply:
      ok = detail::write_ply_soup(stream, mesh.vertices, mesh.faces);
      break;
  }
  if (!ok) throw InputError(name, 0, "cannot format the mesh for writing");
  write_file_atomically(file, stream.str());
}

}  // namespace posekit
