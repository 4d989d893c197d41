// Generalized winding numbers of a closed triangle surface: how many times the surface wraps around
// a point (about 1 inside, 0 outside, 1/2 on the surface). On a surface that intersects itself a
// point inside two parts at once reads about 2, and a point of one part lying inside another 3/2.
#pragma once

#include <Eigen/Core>

namespace posekit {

/// Winding number of the surface (#V by 3 `vertices`, #F by 3 `faces`) at each of the #P by 3
/// `points`: the sum of the solid angles its faces subtend, over 4 pi. Faces near a point count
/// exactly, far clusters by their dipole (error below 0.02): O(#F log #F + #P log #F), parallel
/// over points.
Eigen::VectorXd winding_numbers(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const Eigen::Ref<const Eigen::MatrixX3d>& points);

}  // namespace posekit
