#include <gtest/gtest.h>

#include <posekit/demo_shape.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/poisson_interpolation.hpp>

#include <Eigen/Geometry>


namespace posekit {
namespace {

Eigen::MatrixX3d rotate(const Eigen::MatrixX3d& vertices, const Eigen::Matrix3d& rotation) {
  return vertices * rotation.transpose();
}

// The lumped-mass centroid, which the interpolation keeps on the linear path.
Eigen::RowVector3d mass_centroid(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces) {
  const Eigen::VectorXd areas = face_areas(vertices, faces);
  Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int corner = 0; corner < 3; ++corner) sum += areas(f) / 3.0 * vertices.row(faces(f, corner));
  }
  return sum / areas.sum();
}

TEST(PoissonInterpolation, EndsReproduceTheInputPoses) {
  const PoseSet arm = make_demo_arm();
  const PoissonInterpolator interpolator(arm.pose(0), arm.pose(2), arm.faces());
  const double scale = bounding_box_diagonal(arm.pose(0));
  EXPECT_LT((interpolator.at(0.0) - arm.pose(0)).cwiseAbs().maxCoeff(), 1e-8 * scale);
  EXPECT_LT((interpolator.at(1.0) - arm.pose(2)).cwiseAbs().maxCoeff(), 1e-8 * scale);
}

TEST(PoissonInterpolation, RigidRotationStaysRigid) {
  const PoseSet arm = make_demo_arm();
  Eigen::MatrixX3d source = arm.pose(0);
  source.rowwise() -= mass_centroid(source, arm.faces());
  const Eigen::Matrix3d quarter_turn = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const PoissonInterpolator interpolator(source, rotate(source, quarter_turn), arm.faces());
  const Eigen::Matrix3d eighth_turn = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const double scale = bounding_box_diagonal(source);
  EXPECT_LT((interpolator.at(0.5) - rotate(source, eighth_turn)).cwiseAbs().maxCoeff(), 1e-5 * scale);
}

TEST(PoissonInterpolation, BendingKeepsEdgeLengthsBetterThanLinearInterpolation) {
  const PoseSet arm = make_demo_arm();
  const PoissonInterpolator interpolator(arm.pose(0), arm.pose(3), arm.faces());
  const Eigen::MatrixX3d middle = interpolator.at(0.5);
  const Eigen::MatrixX3d linear = 0.5 * (arm.pose(0) + arm.pose(3));
  // The linear blend collapses the far end of a 135-degree bend; gradient-space interpolation keeps
  // the arm's surface area close to the rest pose's.
  const double rest_area = face_areas(arm.pose(0), arm.faces()).sum();
  const double poisson_area = face_areas(middle, arm.faces()).sum();
  const double linear_area = face_areas(linear, arm.faces()).sum();
  EXPECT_LT(std::abs(poisson_area - rest_area), 0.5 * std::abs(linear_area - rest_area));
  EXPECT_LT(std::abs(poisson_area - rest_area), 0.05 * rest_area);
}

TEST(PoissonInterpolation, HalfTurnTwistIsContinuousAcrossFaces) {
  // A tube twisted progressively up to 180 degrees at its end: faces at the end rotate by nearly pi,
  // and a per-face choice of rotation direction would tear the in-between pose apart.
  const PoseSet arm = make_demo_arm();
  Eigen::MatrixX3d twisted = arm.pose(0);
  const double length = arm.pose(0).col(0).maxCoeff() - arm.pose(0).col(0).minCoeff();
  const double start = arm.pose(0).col(0).minCoeff();
  for (Eigen::Index v = 0; v < twisted.rows(); ++v) {
    const double angle = M_PI * (twisted(v, 0) - start) / length;
    twisted.row(v) = (Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()) * arm.pose(0).row(v).transpose()).transpose();
  }
  const PoissonInterpolator interpolator(arm.pose(0), twisted, arm.faces());
  const Eigen::MatrixX3d middle = interpolator.at(0.5);
  const double rest_area = face_areas(arm.pose(0), arm.faces()).sum();
  EXPECT_LT(std::abs(face_areas(middle, arm.faces()).sum() - rest_area), 0.02 * rest_area);
}

TEST(PoissonInterpolation, KeyFramesAreEvenlySpaced) {
  const PoseSet arm = make_demo_arm();
  const PoissonInterpolator interpolator(arm.pose(0), arm.pose(1), arm.faces());
  const std::vector<Eigen::MatrixX3d> frames = interpolator.key_frames(5);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_LT((frames[2] - interpolator.at(0.5)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(interpolator.key_frames(1), ArgumentError);
}

TEST(PoissonInterpolation, RejectsMismatchedPoses) {
  const PoseSet arm = make_demo_arm();
  const Eigen::MatrixX3d fewer = arm.pose(1).topRows(10);
  EXPECT_THROW(PoissonInterpolator(arm.pose(0), fewer, arm.faces()), ArgumentError);
}

}  // namespace
}  // namespace posekit
