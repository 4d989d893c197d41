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

// `result` with the region's vertices moved as-rigid-as-possible towards the reference's shape of
// the region, the ring around it held at its place in `result`. Nothing where the region's
// surface is not a manifold CGAL can take, or where the solve fails.
std::optional<Eigen::MatrixX3d> relaxed(const Eigen::MatrixX3d& result, const Eigen::MatrixX3d& reference,
                                        const Eigen::MatrixX3i& faces, const std::vector<char>& region,
                                        const AdjacencyLists& neighbours) {
  const std::vector<char> with_rim = within_rings(region, neighbours, 1);
  std::vector<int> original;
  const Mesh part = submesh(reference, faces, faces_within(with_rim, faces), &original);

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
  for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
    const MeshVertex vertex(static_cast<unsigned>(v));
    const int w = original[static_cast<size_t>(v)];
    if (region[static_cast<size_t>(w)] != 0) {
      deformation.insert_roi_vertex(vertex);
    } else {
      deformation.insert_control_vertex(vertex);
      deformation.set_target_position(vertex, Kernel::Point_3(result(w, 0), result(w, 1), result(w, 2)));
    }
  }
  if (!deformation.preprocess()) return std::nullopt;
  deformation.deform(kIterations, kEnergyTolerance);

  Eigen::MatrixX3d candidate = result;
  for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
    const int w = original[static_cast<size_t>(v)];
    if (region[static_cast<size_t>(w)] == 0) continue;
    const Kernel::Point_3& p = mesh.point(MeshVertex(static_cast<unsigned>(v)));
    candidate.row(w) << p.x(), p.y(), p.z();
    if (!candidate.row(w).allFinite()) return std::nullopt;
  }
  return candidate;
}

}  // namespace

RelaxationResult relax_folded_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& reference,
                                      const Eigen::MatrixX3i& faces, const std::vector<int>& reference_intersecting) {
  const auto vertex_count = static_cast<size_t>(result.rows());
  const auto new_faces = [&](const Eigen::MatrixX3d& pose) {
    return new_intersecting_faces(self_intersecting_faces(pose, faces), reference_intersecting);
  };
  RelaxationResult out;
  std::vector<int> current = new_faces(result);
  out.new_faces_before = static_cast<int>(current.size());
  const AdjacencyLists neighbours = vertex_neighbours(faces, static_cast<int>(vertex_count));
  std::vector<char> moved(vertex_count, 0);

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
        std::vector<char> region = within_rings(core, neighbours, margin);
        if (static_cast<double>(std::count(region.begin(), region.end(), 1)) >
            kLargestRegionFraction * static_cast<double>(vertex_count)) {
          break;
        }
        std::optional<Eigen::MatrixX3d> candidate = relaxed(result, reference, faces, region, neighbours);
        if (!candidate) continue;
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
