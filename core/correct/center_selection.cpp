#include "correct/center_selection.hpp"

#include <posekit/error.hpp>

#include <nanoflann.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <string>

namespace posekit::detail {
namespace {

using Eigen::Index;

using CenterTree = nanoflann::KDTreeEigenMatrixAdaptor<Points4, 4, nanoflann::metric_L2_Simple>;

double squared_distance(const Points4& positions, Index i, const Eigen::RowVector4d& point) {
  return (positions.row(i) - point).squaredNorm();
}

Index farthest_from(const Points4& positions, const Eigen::RowVector4d& point) {
  Index farthest = 0;
  double largest = -1.0;
  for (Index i = 0; i < positions.rows(); ++i) {
    const double d = squared_distance(positions, i, point);
    if (d > largest) {
      largest = d;
      farthest = i;
    }
  }
  return farthest;
}

}  // namespace

std::pair<Index, Index> approximately_farthest_pair(const Points4& positions) {
  if (positions.rows() == 0) {
    throw ArgumentError("approximately_farthest_pair: positions is empty");
  }
  const Eigen::RowVector4d centroid = positions.colwise().mean();
  Index first = farthest_from(positions, centroid);
  Index second = farthest_from(positions, positions.row(first));
  // Each sweep can only lengthen the pair (the old end is a candidate of the new search).
  for (int sweep = 0; sweep < 2; ++sweep) {
    first = farthest_from(positions, positions.row(second));
    second = farthest_from(positions, positions.row(first));
  }
  return {first, second};
}

std::vector<Index> spread_centers(const Points4& positions, Index count, double min_separation) {
  std::vector<Index> chosen;
  if (count <= 0 || positions.rows() == 0) return chosen;
  const double coincident = min_separation * min_separation;
  // nearest[i]: squared distance from point i to the closest chosen point.
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(positions.rows(),
                                                      std::numeric_limits<double>::infinity());
  const auto take = [&](Index index) {
    chosen.push_back(index);
    const Eigen::RowVector4d point = positions.row(index);
    for (Index i = 0; i < positions.rows(); ++i) {
      nearest(i) = std::min(nearest(i), squared_distance(positions, i, point));
    }
  };
  const auto [first, second] = approximately_farthest_pair(positions);
  take(first);
  while (static_cast<Index>(chosen.size()) < count) {
    Index next = 0;
    // The second end of the farthest pair is also the point farthest from the first.
    if (chosen.size() == 1) {
      next = second;
    } else {
      nearest.maxCoeff(&next);
    }
    if (!(nearest(next) > coincident)) break;
    take(next);
  }
  return chosen;
}

namespace {

// Constraints that are not centers and still miss the tolerance: the `candidates` worst of them,
// worst first; ties by index so that the choice does not depend on the sort.
std::vector<Index> worst_candidates(const Eigen::VectorXd& squared_errors,
                                    const std::vector<bool>& is_center,
                                    const CenterCandidates& selection) {
  std::vector<Index> pool;
  for (Index i = 0; i < squared_errors.size(); ++i) {
    if (!is_center[static_cast<std::size_t>(i)] &&
        squared_errors(i) >= selection.max_squared_error) {
      pool.push_back(i);
    }
  }
  const std::size_t kept = std::min(pool.size(), static_cast<std::size_t>(std::max(selection.candidates, 0)));
  std::partial_sort(pool.begin(), pool.begin() + static_cast<std::ptrdiff_t>(kept), pool.end(),
                    [&](Index a, Index b) {
                      return squared_errors(a) > squared_errors(b) ||
                             (squared_errors(a) == squared_errors(b) && a < b);
                    });
  pool.resize(kept);
  return pool;
}

// Squared distance from each candidate to its nearest center (infinity when there is none).
std::vector<double> squared_distances_to_centers(const Points4& positions,
                                                 const std::vector<Index>& candidates,
                                                 const Points4& centers) {
  std::vector<double> nearest(candidates.size(), std::numeric_limits<double>::infinity());
  if (centers.rows() == 0) return nearest;
  const CenterTree tree(4, std::cref(centers), 16);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Eigen::RowVector4d query = positions.row(candidates[k]);
    Index neighbour = 0;
    double distance = 0;
    tree.query(query.data(), 1, &neighbour, &distance);
    nearest[k] = distance;
  }
  return nearest;
}

}  // namespace

std::vector<Index> select_new_centers(const Points4& positions,
                                      const Eigen::VectorXd& squared_errors,
                                      const std::vector<bool>& is_center, const Points4& centers,
                                      const CenterCandidates& selection) {
  const Index count = positions.rows();
  if (squared_errors.size() != count || static_cast<Index>(is_center.size()) != count) {
    throw ArgumentError("select_new_centers: " + std::to_string(count) + " positions but " +
                        std::to_string(squared_errors.size()) + " errors and " +
                        std::to_string(is_center.size()) + " center flags");
  }
  const std::vector<Index> candidates = worst_candidates(squared_errors, is_center, selection);
  // nearest[k]: squared distance from candidate k to the closest center, existing or chosen.
  std::vector<double> nearest = squared_distances_to_centers(positions, candidates, centers);
  const double coincident = selection.min_separation * selection.min_separation;
  std::vector<bool> available(candidates.size());
  for (std::size_t k = 0; k < candidates.size(); ++k) available[k] = nearest[k] > coincident;

  std::vector<Index> chosen;
  while (static_cast<int>(chosen.size()) < selection.count) {
    // The first pick is the worst fitted candidate; each later one the farthest from all centers.
    std::size_t best = candidates.size();
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (available[k] && (best == candidates.size() || nearest[k] > nearest[best])) {
        best = k;
        if (chosen.empty()) break;
      }
    }
    if (best == candidates.size()) break;
    chosen.push_back(candidates[best]);
    available[best] = false;
    const Eigen::RowVector4d point = positions.row(candidates[best]);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (!available[k]) continue;
      nearest[k] = std::min(nearest[k], squared_distance(positions, candidates[k], point));
      available[k] = nearest[k] > coincident;
    }
  }
  return chosen;
}

}  // namespace posekit::detail
