// Where the greedy RBF fit puts its centers: spread-out starting centers, then each round a batch
// of badly fitted constraints that lie far from each other and from the centers in place.
#pragma once

#include <posekit/device.hpp>

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace posekit::detail {

/// Two rows of `positions` (#P by 4, #P >= 1) that are nearly the most distant pair. An exact
/// diameter costs O(P^2); this is the usual double sweep: the point farthest from the centroid,
/// the point farthest from it, then the point farthest from that, repeated twice. The result is at
/// least half the true diameter and nearly always within a few percent of it.
std::pair<Eigen::Index, Eigen::Index> approximately_farthest_pair(const Points4& positions);

/// Indices of up to `count` rows of `positions` (#P by 4) spread over them: the two ends of
/// approximately_farthest_pair(), then farthest-point sampling (each next point the farthest from
/// those already taken). Stops early when every remaining point lies within `min_separation` of a
/// taken one, so no two results coincide.
std::vector<Eigen::Index> spread_centers(const Points4& positions, Eigen::Index count,
                                         double min_separation);

/// Which constraints become centers in one round of the greedy fit.
struct CenterCandidates {
  int candidates = 1024;           ///< p: how many of the worst constraints are considered
  int count = 128;                 ///< m: how many of them are chosen at most
  double max_squared_error = 0;    ///< constraints whose squared error is below this are fine
  double min_separation = 0;       ///< a point closer than this to a center would duplicate it
};

/// Chooses new centers among the constraints (#P by 4 `positions`, #P `squared_errors`) that are
/// not centers yet (`is_center`, #P flags): of the `candidates` worst ones at or above
/// max_squared_error, the worst first, then repeatedly the one farthest from every center (the
/// current `centers`, #C by 4, through a kd-tree, and those chosen before it). Candidates within
/// min_separation of a center are skipped. Returns their indices, at most `count`, in the order
/// chosen; empty when no candidate qualifies.
std::vector<Eigen::Index> select_new_centers(const Points4& positions,
                                             const Eigen::VectorXd& squared_errors,
                                             const std::vector<bool>& is_center,
                                             const Points4& centers,
                                             const CenterCandidates& selection);

}  // namespace posekit::detail
