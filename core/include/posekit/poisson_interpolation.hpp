// Gradient-space (Poisson) shape interpolation between two poses of one connectivity.
//
// Each face's deformation gradient from the source to the target pose is split by polar
// decomposition into a rotation and a symmetric stretch; at time t the rotation is exp(t log R)
// and the stretch (1 - t) I + t S. The in-between pose is the least-squares mesh whose per-face
// gradients best match these, found with one sparse solve against a matrix factorized once.
#pragma once

#include <posekit/mesh.hpp>

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace posekit {

/// Interpolates from a source to a target pose; keeps its factorization for many times t.
class PoissonInterpolator {
 public:
  /// `source` and `target` are #V by 3 poses of the #F by 3 `faces`. Throws ArgumentError when the
  /// sizes differ or a face index is out of range.
  PoissonInterpolator(const Eigen::Ref<const Eigen::MatrixX3d>& source,
                      const Eigen::Ref<const Eigen::MatrixX3d>& target,
                      const Eigen::Ref<const Eigen::MatrixX3i>& faces);
  ~PoissonInterpolator();
  PoissonInterpolator(PoissonInterpolator&&) noexcept;
  PoissonInterpolator& operator=(PoissonInterpolator&&) noexcept;

  /// The #V by 3 pose at time t (0 gives the source, 1 the target, up to round-off).
  Eigen::MatrixX3d at(double t) const;

  /// `count` >= 2 poses at the evenly spaced times 0, 1/(count-1), ..., 1.
  std::vector<Eigen::MatrixX3d> key_frames(int count) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace posekit
