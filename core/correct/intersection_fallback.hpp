// The fallback for what integration cannot deliver: where the result still has intersections the
// reference does not have, the region around them is taken from the target, as the method's
// authors do for global intersections (a part of the key frames passing through another part on
// the way to a target where the two do not touch). Such a part is dragged along by the obstacle,
// so the region follows the vertices that strayed far from the target; smaller residues (an
// intersection the reference already had sliding onto a neighbouring face, a fold where the flow
// compresses the surface below the edge length) need only a few rings.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace posekit::detail {

struct FallbackResult {
  int regions = 0;            ///< regions taken from the target
  int vertices = 0;           ///< vertices taken from the target (blended ones included)
  int global_regions = 0;     ///< of those, regions the key frames pass through another part
  int smoothed_regions = 0;   ///< small regions smoothed instead, where the target's shape did not help
  int rejected_regions = 0;   ///< regions left as integrated: the target's region did not help
  int new_faces_before = 0;   ///< new intersecting faces of the integrated result
};

/// Gives regions of `result` (#V by 3) the shape of `target` until no face intersects that is not in
/// `reference_intersecting` (sorted), or no replacement helps. A region grows from the vertices of
/// the new faces by one and three rings; where it touches `in_transit` vertices (those only the
/// in-between key frames made unconstrained: a global intersection) also through the vertices
/// farther than `deviation_threshold` from the target. The region takes the target's positions plus
/// the harmonic interpolation of the offsets result - target around it, and is kept only when that
/// lowers the number of new intersecting faces. Where no such region helps, the new faces' vertices
/// (and then one more ring) are tried as a harmonic membrane over their surroundings, which undoes
/// folds inside corrected regions where the target cannot help.
FallbackResult restore_target_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& target,
                                      const std::vector<int>& reference_intersecting, const Eigen::MatrixX3i& faces,
                                      const std::vector<char>& in_transit, double deviation_threshold);

}  // namespace posekit::detail
