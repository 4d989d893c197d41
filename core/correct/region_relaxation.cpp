#include "correct/region_relaxation.hpp"

#include "correct/vertex_regions.hpp"

#include <posekit/self_intersections.hpp>
#include <posekit/submesh.hpp>
#include <posekit/topology.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_deformation.h>

#include <algorithm>
#include <optional>
#include <utility>

namespace posekit::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using TriangleMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using MeshVertex = TriangleMesh::Vertex_index;
using Deformation = CGAL::Surface_mesh_deformation<TriangleMesh, CGAL::Default, CGAL::Default, CGAL::SRE_ARAP>;

// Margins tried around a fold, smallest first: a crease needs a ring or two, a part folded through
// itself (lion-08, lion-09) six to twelve.
constexpr int kMarginRings[] = {1, 2, 3, 4, 6, 8, 12, 16};

// Beyond this fraction of the vertices a region is no longer a fold but the pose.
constexpr double kLargestRegionFraction = 0.25;

// Rounds of the passes at most: a relaxation can uncover a crease next to it.
constexpr int kRounds = 3;

// Local/global iterations, and the relative change of the energy at which they stop earlier.
constexpr unsigned kIterations = 20;
constexpr double kEnergyTolerance = 1e-5;

}  // namespace

std::optional<Eigen::MatrixX3d> as_rigid_as_possible(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3d& current,
                                                     const Eigen::MatrixX3i& faces, const std::vector<char>& free,
                                                     const std::vector<char>& handles,
                                                     const Eigen::MatrixX3d& handle_positions,
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
  const auto hold = [&](MeshVertex vertex, const Eigen::MatrixX3d& positions, int row) {
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

RelaxationResult relax_folded_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& reference,
                                      const Eigen::MatrixX3i& faces, const std::vector<int>& reference_intersecting,
                                      const RelaxationLimits& limits) {
  const auto vertex_count = static_cast<size_t>(result.rows());
  const auto new_faces = [&](const Eigen::MatrixX3d& pose) {
    return new_intersecting_faces(self_intersecting_faces(pose, faces), reference_intersecting);
  };
  RelaxationResult out;
  std::vector<int> current = new_faces(result);
  out.new_faces_before = static_cast<int>(current.size());
  const AdjacencyLists neighbours = vertex_neighbours(faces, static_cast<int>(vertex_count));
  std::vector<char> moved(vertex_count, 0);
  const std::vector<char> no_handles(vertex_count, 0);

  for (int round = 0; round < kRounds && !current.empty(); ++round) {
    const int regions_before = out.regions;
    for (const std::vector<int>& component :
         connected_sets(within_rings(face_vertices(current, faces, vertex_count), neighbours, 1), neighbours)) {
      if (current.empty()) break;
      std::vector<char> core(vertex_count, 0);
      for (int v : component) core[static_cast<size_t>(v)] = 1;
      if (!touches(core, current, faces)) continue;  // an earlier relaxation settled this one

      std::vector<int> best_faces = current;
      std::optional<Eigen::MatrixX3d> best;
      std::vector<char> best_region;
      for (const int margin : kMarginRings) {
        if (margin > limits.widest_margin) break;
        std::vector<char> region = within_rings(core, neighbours, margin);
        if (static_cast<double>(std::count(region.begin(), region.end(), 1)) >
            kLargestRegionFraction * static_cast<double>(vertex_count)) {
          break;
        }
        std::optional<Eigen::MatrixX3d> candidate =
            as_rigid_as_possible(reference, result, faces, region, no_handles, result, neighbours);
        if (!candidate) continue;
        if (((*candidate - result).rowwise().norm().array() > limits.largest_move).any()) continue;
        std::vector<int> remaining = new_faces(*candidate);
        if (remaining.size() >= best_faces.size()) continue;
        best_faces = std::move(remaining);
        best = std::move(candidate);
        best_region = std::move(region);
        // Nothing left in or at the region: a larger one would only lose more of the pose.
        if (!touches(within_rings(best_region, neighbours, 1), best_faces, faces)) break;
      }
      if (!best) continue;
      result = std::move(*best);
      current = std::move(best_faces);
      ++out.regions;
      for (size_t v = 0; v < vertex_count; ++v) moved[v] = moved[v] != 0 || best_region[v] != 0;
    }
    if (out.regions == regions_before) break;
  }
  out.new_faces_after = static_cast<int>(current.size());
  out.vertices = static_cast<int>(std::count(moved.begin(), moved.end(), 1));
  return out;
}

}  // namespace posekit::detail
