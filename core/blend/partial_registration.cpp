#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/partial_registration.hpp>
#include <posekit/topology.hpp>

#include "blend/closest_point.hpp"

#include <Eigen/Geometry>
#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace posekit {
namespace {

using Clock = std::chrono::steady_clock;
using VertexTree = nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixX3d, 3, nanoflann::metric_L2_Simple>;

constexpr double kPi = 3.14159265358979323846;

struct Match {
  int face = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  double distance = std::numeric_limits<double>::infinity();
};

void check_scan_inputs(const Mesh& scan, const ScanFitOptions& o) {
  if (scan.vertices.rows() == 0) throw ArgumentError("the scan has no vertex");
  if (!scan.vertices.allFinite()) throw ArgumentError("the scan has a non-finite coordinate");
  check_face_indices(scan.faces, static_cast<int>(scan.vertices.rows()));
  if (o.iterations < 0 || o.round_average_iterations < 0 || o.round_minimal_iterations < 0) {
    throw ArgumentError("scan fit: iteration counts must be >= 0");
  }
  if (o.max_scan_points < 1) throw ArgumentError("scan fit: max_scan_points must be >= 1");
  if (!(o.scan_weight > 0.0) || !std::isfinite(o.scan_weight)) throw ArgumentError("scan fit: scan_weight must be > 0");
  if (!(o.max_normal_angle_degrees > 0.0 && o.max_normal_angle_degrees <= 180.0)) {
    throw ArgumentError("scan fit: max_normal_angle_degrees must lie in (0, 180]");
  }
  if (!(o.rejection_factor > 0.0) || !std::isfinite(o.rejection_factor)) {
    throw ArgumentError("scan fit: rejection_factor must be > 0");
  }
}

}  // namespace

ScanRegistration fit_to_scan(BlendedDeformer& deformer, const Mesh& scan, const std::vector<LinearConstraint>& fixed,
                             const Eigen::Ref<const Eigen::MatrixX3d>& fixed_targets, const BlendResult& start,
                             const ScanFitOptions& options) {
  const Clock::time_point begin = Clock::now();
  check_scan_inputs(scan, options);
  if (static_cast<Eigen::Index>(fixed.size()) != fixed_targets.rows()) {
    throw ArgumentError(std::to_string(fixed.size()) + " fixed constraints but " + std::to_string(fixed_targets.rows()) +
                        " targets");
  }
  const Eigen::MatrixX3i& faces = deformer.faces();
  const AdjacencyLists faces_of_vertex = vertex_faces(faces, deformer.vertex_count());
  const int scan_count = static_cast<int>(scan.vertices.rows());
  const int sample_count = std::min(scan_count, options.max_scan_points);
  std::vector<int> samples(static_cast<size_t>(sample_count));
  for (int s = 0; s < sample_count; ++s) {
    samples[static_cast<size_t>(s)] = static_cast<int>((static_cast<long long>(s) * scan_count) / sample_count);
  }
  const Eigen::MatrixX3d scan_normals = vertex_normals(scan.vertices, scan.faces);
  const double cos_limit = std::cos(options.max_normal_angle_degrees * kPi / 180.0);

  ScanRegistration registration;
  BlendResult current = start;
  for (int round = 0; round < options.iterations; ++round) {
    const Clock::time_point round_start = Clock::now();
    const Eigen::MatrixX3d& mesh = current.vertices;
    const Eigen::MatrixX3d normals = face_normals(mesh, faces);
    const VertexTree tree(3, std::cref(mesh), 16);
    std::vector<Match> matches(samples.size());
    tbb::parallel_for(size_t{0}, samples.size(), [&](size_t s) {
      const Eigen::RowVector3d p = scan.vertices.row(samples[s]);
      Eigen::Index nearest = 0;
      double squared = 0.0;
      tree.query(p.data(), 1, &nearest, &squared);
      Match best;
      for (int f : faces_of_vertex[static_cast<int>(nearest)]) {
        const Eigen::Vector3d b = detail::closest_point_barycentric(p, mesh.row(faces(f, 0)), mesh.row(faces(f, 1)),
                                                                    mesh.row(faces(f, 2)));
        const Eigen::RowVector3d q = b(0) * mesh.row(faces(f, 0)) + b(1) * mesh.row(faces(f, 1)) + b(2) * mesh.row(faces(f, 2));
        const double d = (p - q).norm();
        if (d < best.distance) best = Match{f, b, d};
      }
      const Eigen::RowVector3d scan_normal = scan_normals.row(samples[s]);
      if (best.face >= 0 && scan_normal.squaredNorm() > 0.0 && scan_normal.dot(normals.row(best.face)) < cos_limit) {
        best.face = -1;
      }
      matches[s] = best;
    });
    std::vector<double> distances;
    for (const Match& m : matches) {
      if (m.face >= 0) distances.push_back(m.distance);
    }
    ScanFitIteration iteration;
    std::vector<LinearConstraint> constraints;
    std::vector<Eigen::RowVector3d> targets;
    for (size_t f = 0; f < fixed.size(); ++f) {
      constraints.push_back(fixed[f]);
      targets.push_back(fixed_targets.row(static_cast<Eigen::Index>(f)));
    }
    if (!distances.empty()) {
      std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
      iteration.median_distance = distances[distances.size() / 2];
      const double limit = options.rejection_factor * iteration.median_distance;
      for (size_t s = 0; s < samples.size(); ++s) {
        const Match& m = matches[s];
        if (m.face < 0 || m.distance > limit) continue;
        constraints.push_back({{faces(m.face, 0), faces(m.face, 1), faces(m.face, 2)},
                               {m.barycentric(0), m.barycentric(1), m.barycentric(2)},
                               options.scan_weight});
        targets.push_back(scan.vertices.row(samples[s]));
        ++iteration.matches;
      }
    }
    Eigen::MatrixX3d target_matrix(static_cast<Eigen::Index>(targets.size()), 3);
    for (size_t r = 0; r < targets.size(); ++r) target_matrix.row(static_cast<Eigen::Index>(r)) = targets[r];
    deformer.set_constraints(constraints);
    current = deformer.deform(target_matrix, current, options.round_average_iterations, options.round_minimal_iterations);
    iteration.energy = current.energy;
    iteration.seconds = std::chrono::duration<double>(Clock::now() - round_start).count();
    registration.iterations.push_back(iteration);
  }

  // Correspondence of every scan vertex: the nearest vertex of the fitted mesh.
  const VertexTree tree(3, std::cref(current.vertices), 16);
  registration.correspondence.resize(scan_count);
  registration.distances.resize(scan_count);
  tbb::parallel_for(0, scan_count, [&](int i) {
    const Eigen::RowVector3d p = scan.vertices.row(i);
    Eigen::Index nearest = 0;
    double squared = 0.0;
    tree.query(p.data(), 1, &nearest, &squared);
    registration.correspondence(i) = static_cast<int>(nearest);
    registration.distances(i) = std::sqrt(squared);
  });
  registration.initial = start;
  registration.deformation = std::move(current);
  registration.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  return registration;
}

ScanRegistration register_partial_scan(BlendedDeformer& deformer, const Mesh& scan, const std::vector<int>& features,
                                       const Eigen::Ref<const Eigen::MatrixX3d>& feature_positions,
                                       const ScanFitOptions& options) {
  const Clock::time_point begin = Clock::now();
  check_scan_inputs(scan, options);
  const FeatureConstraints fixed = feature_constraints(deformer, scan, features, feature_positions, options);
  deformer.set_constraints(fixed.constraints);
  const BlendResult initial = deformer.deform(fixed.targets);
  ScanRegistration registration = fit_to_scan(deformer, scan, fixed.constraints, fixed.targets, initial, options);
  registration.feature_discs = fixed.discs;
  registration.seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  return registration;
}

}  // namespace posekit
