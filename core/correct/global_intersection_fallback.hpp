// The fallback for global intersections (a part of the key frames passing through another part on
// the way to a target where the two do not touch): the field cannot reproduce such a motion, so the
// affected region is taken from the target instead, where that adds no intersection.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace posekit::detail {

struct FallbackResult {
  int regions = 0;   ///< regions copied from the target
  int vertices = 0;  ///< vertices copied from the target
  int rejected_regions = 0;  ///< candidate regions left as integrated because copying would intersect
};

/// `in_transit` flags the vertices that were unconstrained only because of intersections in the
/// in-between key frames (not in the target). Each connected region of them whose integrated
/// position strays from the target by more than `deviation_threshold` is replaced in `result` by the
/// target's positions, unless that adds faces intersecting that are not in `reference_intersecting`
/// (the sorted intersecting faces of the reference pose).
FallbackResult restore_unreachable_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& target,
                                           const std::vector<int>& reference_intersecting,
                                           const Eigen::MatrixX3i& faces, const std::vector<char>& in_transit,
                                           double deviation_threshold);

}  // namespace posekit::detail
