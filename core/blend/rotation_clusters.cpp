#include <posekit/error.hpp>
#include <posekit/rotation_clusters.hpp>
#include <posekit/topology.hpp>

#include "blend/rotation_fit.hpp"

#include <Eigen/Geometry>

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <string>

namespace posekit {
namespace {

double surface_area(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVector3d a = vertices.row(faces(f, 0));
    area += 0.5 * (vertices.row(faces(f, 1)) - a).cross(vertices.row(faces(f, 2)) - a).norm();
  }
  return area;
}

Eigen::MatrixXd cluster_features(const std::vector<Eigen::MatrixX3d>& examples,
                                 const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                 double position_weight) {
  const Eigen::MatrixX3d& reference = examples.front();
  const int vertex_count = static_cast<int>(reference.rows());
  const int example_count = static_cast<int>(examples.size());
  const AdjacencyLists ring = vertex_neighbours(faces, vertex_count);
  const double area = surface_area(reference, faces);
  const double length = area > 0.0 ? std::sqrt(area) : 1.0;
  Eigen::MatrixXd features(vertex_count, 3 + 9 * (example_count - 1));
  const double rotation_weight = example_count > 1 ? 1.0 / std::sqrt(example_count - 1.0) : 0.0;
  tbb::parallel_for(0, vertex_count, [&](int v) {
    features.block<1, 3>(v, 0) = position_weight / length * reference.row(v);
    for (int k = 1; k < example_count; ++k) {
      Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
      for (int u : ring[v]) {
        const Eigen::Vector3d posed = (examples[static_cast<size_t>(k)].row(u) - examples[static_cast<size_t>(k)].row(v)).transpose();
        const Eigen::Vector3d rest = (reference.row(u) - reference.row(v)).transpose();
        covariance += posed * rest.transpose();
      }
      const Eigen::Matrix3d rotation = ring[v].empty() ? Eigen::Matrix3d::Identity() : detail::closest_rotation(covariance);
      for (int e = 0; e < 9; ++e) features(v, 3 + 9 * (k - 1) + e) = rotation_weight * rotation(e % 3, e / 3);
    }
  });
  return features;
}

}  // namespace

std::vector<int> rotation_clusters(const std::vector<Eigen::MatrixX3d>& examples,
                                   const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                   int count, double position_weight) {
  if (examples.empty()) throw ArgumentError("rotation_clusters: no example pose");
  const int vertex_count = static_cast<int>(examples.front().rows());
  for (const Eigen::MatrixX3d& example : examples) {
    if (example.rows() != vertex_count) throw ArgumentError("rotation_clusters: the examples differ in vertex count");
  }
  check_face_indices(faces, vertex_count);
  if (count < 1 || count > vertex_count) {
    throw ArgumentError("rotation_clusters: count is " + std::to_string(count) + "; it must lie in [1, " +
                        std::to_string(vertex_count) + "]");
  }
  const Eigen::MatrixXd features = cluster_features(examples, faces, position_weight);

  // Farthest-first centers in space (not in the full features, where a few vertices with a crushed
  // one-ring, such as the inner side of a strongly bent joint, would each take a cluster), starting
  // from the vertex nearest the centroid; Lloyd's iterations then follow the motion.
  Eigen::MatrixXd centers(count, features.cols());
  {
    const Eigen::MatrixXd& positions = examples.front();
    const Eigen::RowVector3d mean = positions.colwise().mean();
    Eigen::Index first = 0;
    (positions.rowwise() - mean).rowwise().squaredNorm().minCoeff(&first);
    centers.row(0) = features.row(first);
    Eigen::VectorXd nearest = (positions.rowwise() - positions.row(first)).rowwise().squaredNorm();
    for (int c = 1; c < count; ++c) {
      Eigen::Index farthest = 0;
      nearest.maxCoeff(&farthest);
      centers.row(c) = features.row(farthest);
      nearest = nearest.cwiseMin((positions.rowwise() - positions.row(farthest)).rowwise().squaredNorm());
    }
  }
  std::vector<int> labels(static_cast<size_t>(vertex_count), 0);
  for (int iteration = 0; iteration < 30; ++iteration) {
    std::atomic<bool> changed{false};
    tbb::parallel_for(0, vertex_count, [&](int v) {
      int best = 0;
      double best_distance = std::numeric_limits<double>::infinity();
      for (int c = 0; c < count; ++c) {
        const double d = (features.row(v) - centers.row(c)).squaredNorm();
        if (d < best_distance) {
          best_distance = d;
          best = c;
        }
      }
      if (labels[static_cast<size_t>(v)] != best) {
        labels[static_cast<size_t>(v)] = best;
        changed.store(true, std::memory_order_relaxed);
      }
    });
    if (!changed.load() && iteration > 0) break;
    Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(count, features.cols());
    Eigen::VectorXi sizes = Eigen::VectorXi::Zero(count);
    for (int v = 0; v < vertex_count; ++v) {
      sums.row(labels[static_cast<size_t>(v)]) += features.row(v);
      ++sizes(labels[static_cast<size_t>(v)]);
    }
    for (int c = 0; c < count; ++c) {
      if (sizes(c) > 0) {
        centers.row(c) = sums.row(c) / sizes(c);
      } else {
        // An empty cluster restarts at the vertex farthest from its own center.
        Eigen::Index farthest = 0;
        Eigen::VectorXd own(vertex_count);
        for (int v = 0; v < vertex_count; ++v) own(v) = (features.row(v) - centers.row(labels[static_cast<size_t>(v)])).squaredNorm();
        own.maxCoeff(&farthest);
        centers.row(c) = features.row(farthest);
        labels[static_cast<size_t>(farthest)] = c;
      }
    }
  }
  // Renumber so that every label in [0, used) is taken.
  std::vector<int> renumber(static_cast<size_t>(count), -1);
  int used = 0;
  for (int& label : labels) {
    if (renumber[static_cast<size_t>(label)] < 0) renumber[static_cast<size_t>(label)] = used++;
    label = renumber[static_cast<size_t>(label)];
  }
  return labels;
}

std::vector<int> weight_clusters(const Eigen::MatrixXd& weights) {
  if (weights.rows() == 0 || weights.cols() == 0) throw ArgumentError("weight_clusters: empty weight matrix");
  std::vector<int> renumber(static_cast<size_t>(weights.cols()), -1);
  std::vector<int> labels(static_cast<size_t>(weights.rows()));
  int used = 0;
  for (Eigen::Index v = 0; v < weights.rows(); ++v) {
    Eigen::Index largest = 0;
    weights.row(v).maxCoeff(&largest);
    if (renumber[static_cast<size_t>(largest)] < 0) renumber[static_cast<size_t>(largest)] = used++;
    labels[static_cast<size_t>(v)] = renumber[static_cast<size_t>(largest)];
  }
  return labels;
}

}  // namespace posekit
