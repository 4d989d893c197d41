// BlendedDeformer: interpolation between two deformations by one global step with interpolated
// rotations, scales and example weights.
#include <posekit/error.hpp>

#include "blend/deformer_state.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace posekit {

Eigen::MatrixX3d BlendedDeformer::interpolate(const BlendResult& a, const BlendResult& b, double t) const {
  if (state_->richer) return state_->richer->interpolate(a, b, t);
  const State& s = *state_;
  if (!(t >= 0.0 && t <= 1.0)) throw ArgumentError("interpolate: t must lie in [0, 1]");
  const size_t blocks = static_cast<size_t>(s.block_count());
  for (const BlendResult* r : {&a, &b}) {
    if (r->rotations.size() != blocks || r->transformations.rows() != s.atom_count() ||
        r->example_weights.size() != s.example_count() || r->example_scales.size() != s.example_count()) {
      throw ArgumentError("interpolate: a deformation was not made by this deformer");
    }
  }
  // The in-between shape comes from the interpolated rotations by a global step of the ARAP energy
  // alone (interpolating the constraint targets on straight lines would pull the shape inwards).
  // What the constraints added to each end (its difference from the ARAP-only shape of its own
  // rotations) is blended linearly, so that t = 0 and t = 1 give a and b exactly.
  const auto free_shape = [&](const std::vector<Eigen::Matrix3d>& rotations, const Eigen::VectorXd& weights,
                              const Eigen::VectorXd& scales) -> Eigen::MatrixX3d {
    return State::solve(s.unconstrained, s.arap_right_side(rotations, weights.cwiseProduct(scales)));
  };
  std::vector<Eigen::Matrix3d> rotations(blocks);
  for (size_t j = 0; j < blocks; ++j) {
    const Eigen::Quaterniond qa(a.rotations[j]);
    const Eigen::Quaterniond qb(b.rotations[j]);
    rotations[j] = qa.slerp(t, qb).toRotationMatrix();
  }
  const Eigen::VectorXd weights = (1.0 - t) * a.example_weights + t * b.example_weights;
  const Eigen::VectorXd scales = (1.0 - t) * a.example_scales + t * b.example_scales;
  const Eigen::MatrixX3d offset_a = a.transformations - free_shape(a.rotations, a.example_weights, a.example_scales);
  const Eigen::MatrixX3d offset_b = b.transformations - free_shape(b.rotations, b.example_weights, b.example_scales);
  return vertices(free_shape(rotations, weights, scales) + (1.0 - t) * offset_a + t * offset_b);
}

}  // namespace posekit
