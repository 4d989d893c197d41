// Where a correction stretched the surface rather than moved it: faces with an edge more than
// twice as long as in both the reference and the target. Edges shorter than a quarter of the
// reference's mean edge length count as that long, so that a sliver which opens to an ordinary face
// does not read as a spike. The one definition the ladder's comparison, the stage that relieves
// stretch and the report share.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace posekit::detail {

/// An edge this many times as long as in both poses counts as stretched.
constexpr double kStretchedFactor = 2.0;
/// ... and this many times as long as strongly stretched.
constexpr double kStronglyStretchedFactor = 3.0;

class StretchMeasure {
 public:
  /// Keeps views of `reference`, `target` (#V by 3) and `faces`, which must outlive the measure.
  StretchMeasure(const Eigen::Ref<const Eigen::MatrixX3d>& reference, const Eigen::Ref<const Eigen::MatrixX3d>& target,
                 const Eigen::Ref<const Eigen::MatrixX3i>& faces);
  /// Per face of `pose`, the edge_stretch against the reference and the target.
  Eigen::VectorXd per_face(const Eigen::Ref<const Eigen::MatrixX3d>& pose) const;
  /// Faces stretched more than `factor`, ascending.
  std::vector<int> stretched_faces(const Eigen::Ref<const Eigen::MatrixX3d>& pose,
                                   double factor = kStretchedFactor) const;
  /// How many faces are stretched more than `factor`.
  int count(const Eigen::Ref<const Eigen::MatrixX3d>& pose, double factor = kStretchedFactor) const;

 private:
  Eigen::Ref<const Eigen::MatrixX3d> reference_;
  Eigen::Ref<const Eigen::MatrixX3d> target_;
  Eigen::Ref<const Eigen::MatrixX3i> faces_;
  double shortest_ = 0;
};

}  // namespace posekit::detail
