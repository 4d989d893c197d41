#include "cgal/arap_deformation.hpp"

#include "cgal/kernel.hpp"

#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

namespace posekit::detail {
namespace {

using TriangleMesh = CGAL::Surface_mesh<ExactPoint>;
using MeshVertex = TriangleMesh::Vertex_index;
using Deformation = CGAL::Surface_mesh_deformation<TriangleMesh, CGAL::Default, CGAL::Default, CGAL::SRE_ARAP>;

}  // namespace

std::optional<Eigen::MatrixX3d> deform_as_rigid_as_possible(const Eigen::Ref<const Eigen::MatrixX3d>& rest,
                                                            const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                                            const std::vector<char>& held,
                                                            const Eigen::Ref<const Eigen::MatrixX3d>& held_positions,
                                                            unsigned iterations, double energy_tolerance) {
  TriangleMesh mesh;
  for (Eigen::Index v = 0; v < rest.rows(); ++v) mesh.add_vertex(exact_point(rest, v));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const auto added = mesh.add_face(MeshVertex(static_cast<unsigned>(faces(f, 0))),
                                     MeshVertex(static_cast<unsigned>(faces(f, 1))),
                                     MeshVertex(static_cast<unsigned>(faces(f, 2))));
    if (added == TriangleMesh::null_face()) return std::nullopt;
  }

  Deformation deformation(mesh);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const MeshVertex vertex(static_cast<unsigned>(v));
    if (held[static_cast<size_t>(v)] != 0) {
      deformation.insert_control_vertex(vertex);
      deformation.set_target_position(vertex, exact_point(held_positions, v));
    } else {
      deformation.insert_roi_vertex(vertex);
    }
  }
  if (!deformation.preprocess()) return std::nullopt;
  deformation.deform(iterations, energy_tolerance);

  Eigen::MatrixX3d deformed(rest.rows(), 3);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const ExactPoint& p = mesh.point(MeshVertex(static_cast<unsigned>(v)));
    deformed.row(v) << p.x(), p.y(), p.z();
  }
  return deformed;
}

}  // namespace posekit::detail
