// A last repair for folds. Where the stages before leave a region folded through itself (the flow
// compressed it below its edge length, a blend or a local correction creased it), the region is
// given back the reference's local shape, as rigidly as possible, with its surroundings held where
// they are. The target cannot help there: the region has strayed from it, or the target is itself
// entangled.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace posekit::detail {

struct RelaxationResult {
  int new_faces_before = 0;  ///< new intersecting faces when the stage began
  int new_faces_after = 0;   ///< and when it ended
  int regions = 0;           ///< regions relaxed and kept
  int vertices = 0;          ///< vertices so moved (each counted once)
};

/// Relaxes regions of `result` (#V by 3) around faces that intersect and are not in
/// `reference_intersecting` (sorted) towards the local shape of `reference` (#V by 3, same frame),
/// as-rigid-as-possible with the ring around each region held at its place in `result`. A region
/// grows from the faces' vertices by 1, 2, 3, 4, 6, 8, 12 and 16 rings, up to a quarter of the
/// vertices, and is kept only when the whole pose then has fewer new intersecting faces; the
/// passes repeat, up to three times, while they help.
RelaxationResult relax_folded_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& reference,
                                      const Eigen::MatrixX3i& faces, const std::vector<int>& reference_intersecting);

}  // namespace posekit::detail
