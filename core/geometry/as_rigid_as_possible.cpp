#include <posekit/as_rigid_as_possible.hpp>
#include <posekit/submesh.hpp>

#include <posekit/vertex_regions.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

namespace posekit {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using TriangleMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using MeshVertex = TriangleMesh::Vertex_index;
using Deformation = CGAL::Surface_mesh_deformation<TriangleMesh, CGAL::Default, CGAL::Default, CGAL::SRE_ARAP>;

// Local/global iterations, and the relative change of the energy at which they stop earlier.
constexpr unsigned kIterations = 20;
constexpr double kEnergyTolerance = 1e-5;

}  // namespace

std::optional<Eigen::MatrixX3d> as_rigid_as_possible(const Eigen::Ref<const Eigen::MatrixX3d>& rest,
                                                     const Eigen::Ref<const Eigen::MatrixX3d>& current,
                                                     const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                                     const std::vector<char>& free,
                                                     const std::vector<char>& handles,
                                                     const Eigen::Ref<const Eigen::MatrixX3d>& handle_positions,
                                                     const AdjacencyLists& neighbours) {
  std::vector<char> moving(free.size());
  for (size_t v = 0; v < free.size(); ++v) moving[v] = free[v] != 0 || handles[v] != 0 ? 1 : 0;
  const std::vector<char> with_rim = within_rings(moving, neighbours, 1);
  std::vector<int> original;
  const Mesh part = submesh(rest, faces, faces_within(with_rim, faces), &original);

  TriangleMesh mesh;
  for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
    mesh.add_vertex(Kernel::Point_3(part.vertices(v, 0), part.vertices(v, 1), part.vertices(v, 2)));
  }
  for (Eigen::Index f = 0; f < part.faces.rows(); ++f) {
    const auto added = mesh.add_face(MeshVertex(static_cast<unsigned>(part.faces(f, 0))),
                                     MeshVertex(static_cast<unsigned>(part.faces(f, 1))),
                                     MeshVertex(static_cast<unsigned>(part.faces(f, 2))));
    if (added == TriangleMesh::null_face()) return std::nullopt;
  }

  Deformation deformation(mesh);
  const auto hold = [&](MeshVertex vertex, const Eigen::Ref<const Eigen::MatrixX3d>& positions, int row) {
    deformation.insert_control_vertex(vertex);
    deformation.set_target_position(vertex, Kernel::Point_3(positions(row, 0), positions(row, 1), positions(row, 2)));
  };
  for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
    const MeshVertex vertex(static_cast<unsigned>(v));
    const int w = original[static_cast<size_t>(v)];
    if (handles[static_cast<size_t>(w)] != 0) {
      hold(vertex, handle_positions, w);
    } else if (free[static_cast<size_t>(w)] != 0) {
      deformation.insert_roi_vertex(vertex);
    } else {
      hold(vertex, current, w);
    }
  }
  if (!deformation.preprocess()) return std::nullopt;
  deformation.deform(kIterations, kEnergyTolerance);

  Eigen::MatrixX3d candidate = current;
  for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
    const int w = original[static_cast<size_t>(v)];
    if (moving[static_cast<size_t>(w)] == 0) continue;
    const Kernel::Point_3& p = mesh.point(MeshVertex(static_cast<unsigned>(v)));
    candidate.row(w) << p.x(), p.y(), p.z();
    if (!candidate.row(w).allFinite()) return std::nullopt;
  }
  return candidate;
}

}  // namespace posekit
