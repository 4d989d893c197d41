#include <posekit/as_rigid_as_possible.hpp>
#include <posekit/submesh.hpp>

#include <posekit/vertex_regions.hpp>

#include "cgal/arap_deformation.hpp"

namespace posekit {
namespace {

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

  // Each vertex of the part is held at its handle position, held where it is, or free.
  std::vector<char> held(static_cast<size_t>(part.vertices.rows()));
  Eigen::MatrixX3d held_positions(part.vertices.rows(), 3);
  for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
    const auto w = static_cast<size_t>(original[static_cast<size_t>(v)]);
    held[static_cast<size_t>(v)] = handles[w] != 0 || free[w] == 0 ? 1 : 0;
    held_positions.row(v) = handles[w] != 0 ? handle_positions.row(static_cast<Eigen::Index>(w))
                                            : current.row(static_cast<Eigen::Index>(w));
  }
  const std::optional<Eigen::MatrixX3d> deformed =
      detail::deform_as_rigid_as_possible(part.vertices, part.faces, held, held_positions, kIterations, kEnergyTolerance);
  if (!deformed) return std::nullopt;

  Eigen::MatrixX3d candidate = current;
  for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
    const int w = original[static_cast<size_t>(v)];
    if (moving[static_cast<size_t>(w)] == 0) continue;
    candidate.row(w) = deformed->row(v);
    if (!candidate.row(w).allFinite()) return std::nullopt;
  }
  return candidate;
}

}  // namespace posekit
