// A second, local correction for what the fallback leaves: where a region had to take the target's
// shape (the field dragged it, or the key frames pass it through another part) and the target is
// itself entangled there, the region alone is corrected again, from the reference's region to the
// region as it now is. On its own the region has no part to pass through, so its own key frames
// and field can do what the whole pose's could not.
#pragma once

#include <posekit/correct.hpp>
#include <posekit/device.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::detail {

struct LocalCorrectionResult {
  int new_faces_before = 0;  ///< new intersecting faces when the stage began
  int new_faces_after = 0;   ///< and when it ended
  int regions = 0;           ///< regions corrected anew and kept
  int vertices = 0;          ///< vertices so changed (each counted once)
};

/// Corrects regions of `result` (#V by 3, the unit-sphere frame of `reference`) around faces that
/// intersect and are not in `reference_intersecting` (sorted), each as a mesh of its own from the
/// reference's positions to the result's with `options` (no local stage inside), blended into the
/// unchanged surroundings over `options.blend_rings` rings, and keeps a region's correction only
/// when the whole pose then has fewer new intersecting faces. A region is grown by 4, 8, then 16
/// rings around the faces, joined with the regions its faces intersect, and left alone beyond half
/// of the vertices; the passes repeat, up to three times, while they help.
LocalCorrectionResult correct_regions_locally(Eigen::MatrixX3d& result, const Eigen::MatrixX3d& reference,
                                              const Eigen::MatrixX3i& faces,
                                              const std::vector<int>& reference_intersecting, Device& device,
                                              const CorrectionOptions& options);

}  // namespace posekit::detail
