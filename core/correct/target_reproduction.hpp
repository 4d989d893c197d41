// Reproduction of the target away from what needed correcting. Integration reproduces every
// constrained vertex only up to the field's fitting error and the integrator's drift; where the
// target has no intersection near a vertex at any time, the target's own position is the right
// answer. The result keeps its integrated displacement from the target on the vertices that were
// not constrained (and a few rings around them) and fades it out smoothly beyond, so the untouched
// parts of the pose equal the target exactly.
#pragma once

#include <posekit/topology.hpp>

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <vector>

namespace posekit::detail {

/// Per-vertex weight of the integrated result: 1 within `keep_rings` edges of a vertex flagged in
/// `corrected`, falling smoothly to 0 over the next `blend_rings` rings, 0 beyond. `neighbours` is
/// the vertex one-ring adjacency.
Eigen::VectorXd correction_weights(const std::vector<char>& corrected, const AdjacencyLists& neighbours,
                                   int keep_rings, int blend_rings);

/// target + weights * (integrated - target), row by row (#V by 3 each, #V weights).
Eigen::MatrixX3d blend_towards_target(const Eigen::Ref<const Eigen::MatrixX3d>& integrated,
                                      const Eigen::Ref<const Eigen::MatrixX3d>& target,
                                      const Eigen::VectorXd& weights);

/// `pose` (#V by 3) with the flagged `region` (one flag per vertex) given the shape of `shape` (#V by
/// 3), displaced by the harmonic interpolation of the offsets pose - shape at the vertices around
/// it: the region keeps the shape's detail and joins its surroundings smoothly, wherever they are.
/// A region that is a whole closed component (no surroundings) takes the shape unmoved.
Eigen::MatrixX3d with_shape_of(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                               const Eigen::Ref<const Eigen::MatrixX3d>& shape,
                               const std::vector<char>& region, const AdjacencyLists& neighbours);

/// The faces of a pose that intersect and are not the reference's (sorted).
using FaceTest = std::function<std::vector<int>(const Eigen::MatrixX3d&)>;

struct ReproductionSettings {
  int keep_rings = 0;      ///< see correction_weights
  int blend_rings = 0;     ///< see correction_weights
  int widening_rings = 0;  ///< rings kept around the vertices of faces a blend made intersect
  int attempts = 1;        ///< blends tried at most
};

struct Reproduction {
  std::optional<Eigen::MatrixX3d> pose;  ///< empty when every attempt made faces intersect
  int reproduced_vertices = 0;           ///< vertices given the target's position exactly
};

/// Blends `result` towards `target`, keeping it around the `kept` vertices (one flag per vertex),
/// and where the blend makes faces intersect that are not in `allowed` (sorted; `new_faces` tells
/// which intersect), keeps the result around those faces too and blends again, up to
/// `settings.attempts` times.
Reproduction reproduce_target(const Eigen::Ref<const Eigen::MatrixX3d>& result,
                              const Eigen::Ref<const Eigen::MatrixX3d>& target, std::vector<char> kept,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces, const AdjacencyLists& neighbours,
                              const ReproductionSettings& settings, const FaceTest& new_faces,
                              const std::vector<int>& allowed);

}  // namespace posekit::detail
