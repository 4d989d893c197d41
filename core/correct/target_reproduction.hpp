// Reproduction of the target away from what needed correcting. Integration reproduces every
// constrained vertex only up to the field's fitting error and the integrator's drift; where the
// target has no intersection near a vertex at any time, the target's own position is the right
// answer. The result keeps its integrated displacement from the target on the vertices that were
// not constrained (and a few rings around them) and fades it out smoothly beyond, so the untouched
// parts of the pose equal the target exactly.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>
#include <vector>

namespace posekit::detail {

/// Per-vertex weight of the integrated result: 1 within `keep_rings` edges of a vertex flagged in
/// `corrected`, falling smoothly to 0 over the next `blend_rings` rings, 0 beyond. `neighbours` is
/// the vertex one-ring adjacency.
Eigen::VectorXd correction_weights(const std::vector<char>& corrected, const AdjacencyLists& neighbours,
                                   int keep_rings, int blend_rings);

/// target + weights * (integrated - target), row by row (#V by 3 each, #V weights).
Eigen::MatrixX3d blend_towards_target(const Eigen::MatrixX3d& integrated, const Eigen::MatrixX3d& target,
                                      const Eigen::VectorXd& weights);

}  // namespace posekit::detail
