// A last repair for folds. Where the stages before leave a region folded through itself (the flow
// compressed it below its edge length, a blend or a local correction creased it), the region is
// given back the reference's local shape, as rigidly as possible, with its surroundings held where
// they are. The target cannot help there: the region has strayed from it, or the target is itself
// entangled.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <limits>
#include <optional>
#include <vector>

namespace posekit::detail {

struct RelaxationResult {
  int new_faces_before = 0;  ///< new intersecting faces when the stage began
  int new_faces_after = 0;   ///< and when it ended
  int regions = 0;           ///< regions relaxed and kept
  int vertices = 0;          ///< vertices so moved (each counted once)
};

/// Bounds of a relaxation.
struct RelaxationLimits {
  int widest_margin = 16;  ///< rings grown around a fold at most (of 1, 2, 3, 4, 6, 8, 12, 16)
  /// A relaxation that moves a vertex farther than this is not kept.
  double largest_move = std::numeric_limits<double>::infinity();
};

/// `current` (#V by 3) with the `free` vertices moved as-rigidly-as-possible towards the local
/// shape of `rest` (same connectivity), the `handles` at their rows of `handle_positions` and the
/// ring around both held at `current`. Nothing where the region's surface is not a manifold CGAL
/// can take, or where the solve fails.
std::optional<Eigen::MatrixX3d> as_rigid_as_possible(const Eigen::MatrixX3d& rest, const Eigen::MatrixX3d& current,
                                                     const Eigen::MatrixX3i& faces, const std::vector<char>& free,
                                                     const std::vector<char>& handles,
                                                     const Eigen::MatrixX3d& handle_positions,
                                                     const AdjacencyLists& neighbours);

/// Relaxes regions of `result` (#V by 3) around faces that intersect and are not in
/// `reference_intersecting` (sorted) towards the local shape of `reference` (#V by 3, same frame),
/// as-rigid-as-possible with the ring around each region held at its place in `result`. A region
/// grows from the faces' vertices by 1, 2, 3, 4, 6, 8, 12 and 16 rings, up to a quarter of the
/// vertices, and is kept only when the whole pose then has fewer new intersecting faces; the
/// passes repeat, up to three times, while they help. `limits` narrows the margins and the moves.
RelaxationResult relax_folded_regions(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& reference,
                                      const Eigen::MatrixX3i& faces, const std::vector<int>& reference_intersecting,
                                      const RelaxationLimits& limits = {});

}  // namespace posekit::detail
