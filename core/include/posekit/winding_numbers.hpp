// Generalized winding numbers of a closed triangle surface: how many times the surface wraps around
// a point (about 1 inside, 0 outside, 1/2 on the surface). On a surface that intersects itself a
// point inside two parts at once reads about 2, and a point of one part lying inside another 3/2.
#pragma once

#include <Eigen/Core>

#include <memory>

namespace posekit {

/// The winding numbers of one surface at any points: its tree of faces is built once, so a caller
/// that asks about the same surface several times pays for the tree once.
class WindingNumberTree {
 public:
  /// Builds the tree of the surface (#V by 3 `vertices`, #F by 3 `faces`): O(#F log #F), the halves
  /// of large subtrees in parallel. Keeps its own copy of both. A tree moved from may only be
  /// assigned to or destroyed.
  WindingNumberTree(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces);
  ~WindingNumberTree();
  WindingNumberTree(WindingNumberTree&&) noexcept;
  WindingNumberTree& operator=(WindingNumberTree&&) noexcept;
  WindingNumberTree(const WindingNumberTree&) = delete;
  WindingNumberTree& operator=(const WindingNumberTree&) = delete;

  /// Winding number at each of the #P by 3 `points`, as winding_numbers() gives it. Parallel over points.
  Eigen::VectorXd at(const Eigen::Ref<const Eigen::MatrixX3d>& points) const;

 private:
  class Tree;
  std::unique_ptr<Tree> tree_;
};

/// Winding number of the surface (#V by 3 `vertices`, #F by 3 `faces`) at each of the #P by 3
/// `points`: the sum of the solid angles its faces subtend, over 4 pi. Faces near a point count
/// exactly, far clusters by their dipole (error below 0.02): O(#F log #F + #P log #F), parallel
/// over points (and over the halves of the tree it builds).
Eigen::VectorXd winding_numbers(const Eigen::Ref<const Eigen::MatrixX3d>& vertices,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const Eigen::Ref<const Eigen::MatrixX3d>& points);

}  // namespace posekit
