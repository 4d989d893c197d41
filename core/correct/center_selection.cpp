#include "correct/center_selection.hpp"

#include <posekit/error.hpp>

#include <nanoflann.hpp>

#include <algorithm>
#include <cstdlib>
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
  std::vector<Index> pool;
  for (Index i = 0; i < count; ++i) {
    if (!is_center[static_cast<std::size_t>(i)] &&
        (std::getenv("PK_ALL") ? true : squared_errors(i) >= selection.max_squared_error)) {
      pool.push_back(i);
    }
  }
  if (pool.empty() || selection.count <= 0 || selection.candidates <= 0) return {};

  // The p worst, worst first; ties by index so that the choice does not depend on the sort.
  const std::size_t kept = std::min(pool.size(), static_cast<std::size_t>(selection.candidates));
  std::partial_sort(pool.begin(), pool.begin() + static_cast<std::ptrdiff_t>(kept), pool.end(),
                    [&](Index a, Index b) {
                      return squared_errors(a) > squared_errors(b) ||
                             (squared_errors(a) == squared_errors(b) && a < b);
                    });
  pool.resize(kept);

  // nearest[k]: squared distance from candidate k to the closest center, existing or chosen.
  std::vector<double> nearest(kept, std::numeric_limits<double>::infinity());
  if (centers.rows() > 0) {
    const CenterTree tree(4, std::cref(centers), 16);
    for (std::size_t k = 0; k < kept; ++k) {
      const Eigen::RowVector4d query = positions.row(pool[k]);
      Index neighbour = 0;
      double distance = 0;
      tree.query(query.data(), 1, &neighbour, &distance);
      nearest[k] = distance;
    }
  }

  const double coincident = selection.min_separation * selection.min_separation;
  std::vector<bool> taken(kept, false);
  std::vector<Index> chosen;
  while (static_cast<int>(chosen.size()) < selection.count) {
    std::size_t best = kept;
    for (std::size_t k = 0; k < kept; ++k) {
      if (taken[k] || !(nearest[k] > coincident)) continue;
      // The first pick is the worst fitted candidate; later picks the one farthest from all.
      if (chosen.empty()) {
        best = k;
        break;
      }
      if (best == kept || nearest[k] > nearest[best]) best = k;
    }
    if (best == kept) break;
    taken[best] = true;
    chosen.push_back(pool[best]);
    const Eigen::RowVector4d point = positions.row(pool[best]);
    for (std::size_t k = 0; k < kept; ++k) {
      if (!taken[k]) nearest[k] = std::min(nearest[k], squared_distance(positions, pool[k], point));
    }
  }
  return chosen;
}

}  // namespace posekit::detail
