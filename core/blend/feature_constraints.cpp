#include <posekit/error.hpp>
#include <posekit/laplace_beltrami.hpp>
#include <posekit/partial_registration.hpp>
#include <posekit/topology.hpp>

#include "blend/edge_distances.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace posekit {
namespace {

// Vertices on an edge that has a single face (the scan's holes and outline).
std::vector<char> boundary_vertices(const Mesh& scan) {
  std::vector<char> boundary(static_cast<size_t>(scan.vertices.rows()), 0);
  if (scan.faces.rows() == 0) return boundary;
  const EdgeMap edges = edge_map(scan.faces);
  const AdjacencyLists faces_of_edge = edge_faces(edges);
  for (Eigen::Index e = 0; e < edges.edges.rows(); ++e) {
    if (faces_of_edge.count(static_cast<int>(e)) == 1) {
      boundary[static_cast<size_t>(edges.edges(e, 0))] = 1;
      boundary[static_cast<size_t>(edges.edges(e, 1))] = 1;
    }
  }
  return boundary;
}

// Lumped masses of a mesh that may have loose vertices (they get none).
Eigen::VectorXd scan_mass(const Mesh& scan) {
  return scan.faces.rows() > 0 ? lumped_mass(scan.vertices, scan.faces) : Eigen::VectorXd::Ones(scan.vertices.rows());
}

// Weight of a vertex at distance t (in disc radii) from the centre: smooth down to 0 at the rim, so
// that the centroid does not jump when the two meshes' distances put a vertex on different sides of it.
double falloff(double t) {
  if (!(t < 1.0)) return 0.0;
  const double u = 1.0 - t * t;
  return u * u;
}

}  // namespace

FeatureConstraints feature_constraints(const BlendedDeformer& deformer, const Mesh& scan, const std::vector<int>& features,
                                       const Eigen::Ref<const Eigen::MatrixX3d>& feature_positions,
                                       const ScanFitOptions& options) {
  if (scan.vertices.rows() == 0) throw ArgumentError("the scan has no vertex");
  if (!scan.vertices.allFinite()) throw ArgumentError("the scan has a non-finite coordinate");
  check_face_indices(scan.faces, static_cast<int>(scan.vertices.rows()));
  if (features.empty()) throw ArgumentError("the scan fit needs at least one feature point");
  if (static_cast<Eigen::Index>(features.size()) != feature_positions.rows()) {
    throw ArgumentError(std::to_string(features.size()) + " feature vertices but " +
                        std::to_string(feature_positions.rows()) + " feature positions");
  }
  if (!feature_positions.allFinite()) throw ArgumentError("a feature position is not finite");
  for (int v : features) {
    if (v < 0 || v >= deformer.vertex_count()) {
      throw ArgumentError("feature vertex " + std::to_string(v) + " is outside [0, " +
                          std::to_string(deformer.vertex_count()) + ")");
    }
  }
  if (options.feature_rings < 0) throw ArgumentError("scan fit: feature_rings must be >= 0");
  if (!(options.feature_radius > 0.0) || !std::isfinite(options.feature_radius)) {
    throw ArgumentError("scan fit: feature_radius must be > 0");
  }
  if (!(options.scan_scale > 0.0) || !std::isfinite(options.scan_scale)) throw ArgumentError("scan fit: scan_scale must be > 0");
  const int count = static_cast<int>(features.size());
  FeatureConstraints result;
  std::vector<Eigen::RowVector3d> targets;
  for (int f = 0; f < count; ++f) {
    result.constraints.push_back(LinearConstraint::vertex(features[static_cast<size_t>(f)]));
    targets.push_back(feature_positions.row(f));
  }

  // The reference in the internal frame has unit area, so radii there are fractions of sqrt(area);
  // on the scan they are in the examples' units times the scan's scale.
  const Eigen::MatrixX3d& reference = deformer.dictionary().examples().front();
  const double scan_radius_scale = options.scan_scale * std::sqrt(deformer.setup_report().reference_area);
  if (options.feature_rings > 0) {
    const AdjacencyLists mesh_ring = vertex_neighbours(deformer.faces(), deformer.vertex_count());
    const AdjacencyLists scan_ring = vertex_neighbours(scan.faces, static_cast<int>(scan.vertices.rows()));
    const Eigen::VectorXd mesh_mass = lumped_mass(reference, deformer.faces());
    const Eigen::VectorXd masses = scan_mass(scan);
    const std::vector<char> boundary = boundary_vertices(scan);
    const double radius = options.feature_radius;
    for (int f = 0; f < count; ++f) {
      Eigen::Index source = 0;
      (scan.vertices.rowwise() - feature_positions.row(f)).rowwise().squaredNorm().minCoeff(&source);
      const Eigen::VectorXd on_mesh = detail::edge_distances(reference, mesh_ring, features[static_cast<size_t>(f)], radius);
      const Eigen::VectorXd on_scan =
          detail::edge_distances(scan.vertices, scan_ring, static_cast<int>(source), radius * scan_radius_scale);
      for (int ring = 1; ring <= options.feature_rings; ++ring) {
        const double r = radius * ring / options.feature_rings;
        LinearConstraint disc;
        double mesh_total = 0.0;
        for (Eigen::Index v = 0; v < on_mesh.size(); ++v) {
          const double w = mesh_mass(v) * falloff(on_mesh(v) / r);
          if (!(w > 0.0)) continue;
          disc.vertices.push_back(static_cast<int>(v));
          disc.coefficients.push_back(w);
          mesh_total += w;
        }
        Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
        double scan_total = 0.0;
        bool whole = true;
        for (Eigen::Index v = 0; v < on_scan.size() && whole; ++v) {
          if (!(on_scan(v) < r * scan_radius_scale)) continue;
          whole = !boundary[static_cast<size_t>(v)];
          const double w = masses(v) * falloff(on_scan(v) / (r * scan_radius_scale));
          centroid += w * scan.vertices.row(v);
          scan_total += w;
        }
        // A disc that is only its centre vertex adds nothing to the point itself.
        if (!whole || disc.vertices.size() < 2 || !(scan_total > 0.0) || !(mesh_total > 0.0)) continue;
        for (double& c : disc.coefficients) c /= mesh_total;
        result.constraints.push_back(std::move(disc));
        targets.push_back(centroid / scan_total);
        ++result.discs;
      }
    }
  }
  result.targets.resize(static_cast<Eigen::Index>(targets.size()), 3);
  for (size_t r = 0; r < targets.size(); ++r) result.targets.row(static_cast<Eigen::Index>(r)) = targets[r];
  return result;
}

}  // namespace posekit
