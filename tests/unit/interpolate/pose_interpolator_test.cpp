// The interpolator and its three methods on posekit's own arm: the end poses come back, weights and
// options are checked, MixIT and the edge-space baseline keep the bones' length where linear vertex
// interpolation shortens them, and meshes in several pieces or with stray vertices work.
#include "interpolation_fixtures.hpp"
#include "test_data.hpp"

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/interpolate.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/rigid_motion.hpp>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace posekit::testing {
namespace {

const InterpolationMethod kMethods[] = {InterpolationMethod::mixit, InterpolationMethod::edge,
                                        InterpolationMethod::vertex};

InterpolationOptions with_method(InterpolationMethod method) {
  InterpolationOptions options;
  options.method = method;
  return options;
}

// Distance from the centre of the arm's upper-bone end (x < 0.5) to that of its lower-bone end (x > 3.5).
double arm_reach(const PoseSet& arm, const Eigen::MatrixX3d& x) {
  Eigen::RowVector3d first = Eigen::RowVector3d::Zero();
  Eigen::RowVector3d last = Eigen::RowVector3d::Zero();
  const std::vector<int> upper = arm_vertices_below(arm, 0.5);
  const std::vector<int> lower = arm_vertices_above(arm, 3.5);
  for (const int v : upper) first += x.row(v) / static_cast<double>(upper.size());
  for (const int v : lower) last += x.row(v) / static_cast<double>(lower.size());
  return (last - first).norm();
}

class EveryMethod : public ::testing::TestWithParam<InterpolationMethod> {};

TEST_P(EveryMethod, EndWeightsGiveTheInputPoses) {
  const PoseSet arm = demo_arm({80.0});
  PoseInterpolator interpolator(arm, with_method(GetParam()));
  const double size = bounding_box_diagonal(arm.pose(0));
  for (int k = 0; k < 2; ++k) {
    const Eigen::MatrixX3d x = interpolator.interpolate(two_pose_weights(k));
    EXPECT_LT(largest_distance(x, arm.pose(k)), 1e-6 * size) << to_string(GetParam()) << " pose " << k;
  }
}

TEST_P(EveryMethod, ReportsItsStagesAndIsRepeatable) {
  const PoseSet arm = demo_arm({60.0});
  PoseInterpolator interpolator(arm, with_method(GetParam()));
  InterpolationStepReport report;
  const Eigen::MatrixX3d first = interpolator.interpolate(two_pose_weights(0.3), &report);
  EXPECT_GT(report.seconds.total, 0.0);
  EXPECT_GE(report.seconds.total, report.seconds.blend);
  EXPECT_TRUE(first.allFinite());
  EXPECT_EQ(interpolator.interpolate(two_pose_weights(0.3)), first);
  EXPECT_GT(interpolator.precomputation_seconds().total, 0.0);
  EXPECT_EQ(interpolator.layout().edge_dimension, 2LL * edge_map(arm.faces()).edges.rows());
}

TEST_P(EveryMethod, ExtrapolatesWithoutNan) {
  const PoseSet arm = demo_arm({60.0}, 16);
  PoseInterpolator interpolator(arm, with_method(GetParam()));
  for (const double t : {-0.5, 1.5, 3.0}) {
    const Eigen::MatrixX3d x = interpolator.interpolate(two_pose_weights(t));
    EXPECT_TRUE(x.allFinite()) << to_string(GetParam()) << " t = " << t;
  }
}

TEST_P(EveryMethod, HandlesATetrahedron) {
  const Mesh tetrahedron = read_mesh(project_test_data() / "valid" / "tetrahedron.obj");
  PoseSet poses(tetrahedron.faces);
  poses.add_pose(tetrahedron.vertices);
  Eigen::MatrixX3d stretched = tetrahedron.vertices;
  stretched.col(2) *= 2.0;
  poses.add_pose(stretched);
  PoseInterpolator interpolator(poses, with_method(GetParam()));
  const Eigen::MatrixX3d x = interpolator.interpolate(two_pose_weights(0.5));
  ASSERT_TRUE(x.allFinite()) << to_string(GetParam());
  EXPECT_TRUE(interpolator.error(x, two_pose_weights(0.5)).finite);
}

INSTANTIATE_TEST_SUITE_P(Methods, EveryMethod, ::testing::ValuesIn(kMethods),
                         [](const auto& info) { return to_string(info.param); });

// The reach of the arm bent rigidly (by skinning) to `degrees`.
double rigid_reach(double degrees) {
  const PoseSet bent = demo_arm({degrees});
  return arm_reach(bent, bent.pose(1));
}

TEST(PoseInterpolator, MixitAndEdgeKeepTheBonesWhereVerticesShortenThem) {
  // Skinning folds the inside of the joint into itself at stronger bends, which no method should be
  // judged on here.
  const PoseSet arm = demo_arm({60.0});
  const Eigen::VectorXd weights = two_pose_weights(0.5);
  std::map<InterpolationMethod, InterpolationError> errors;
  std::map<InterpolationMethod, double> bends;
  for (const InterpolationMethod method : kMethods) {
    PoseInterpolator interpolator(arm, with_method(method));
    const Eigen::MatrixX3d x = interpolator.interpolate(weights);
    errors[method] = interpolator.error(x, weights);
    bends[method] = arm_bend_degrees(arm, x);
    const double reach = arm_reach(arm, x);
    if (method == InterpolationMethod::vertex) {
      // Linear vertex interpolation cuts the corner: the lower bone comes out shorter.
      EXPECT_NEAR(bends[method], 30.0, 1.0);
      EXPECT_LT(reach, rigid_reach(bends[method]) - 0.05);
      continue;
    }
    // About half the bend (edge-space blends of this skinned joint bend a little less), with bones
    // of their own length.
    EXPECT_NEAR(bends[method], 28.0, 4.0) << to_string(method);
    EXPECT_NEAR(reach, rigid_reach(bends[method]), 0.03) << to_string(method);
    EXPECT_EQ(errors[method].collapsed_faces, 0) << to_string(method);
    EXPECT_EQ(errors[method].flipped_faces, 0) << to_string(method);
  }
  EXPECT_NEAR(bends[InterpolationMethod::mixit], bends[InterpolationMethod::edge], 3.0);
  const double vertex_error = errors[InterpolationMethod::vertex].edge_length.p99;
  EXPECT_LT(errors[InterpolationMethod::mixit].edge_length.p99, 0.3 * vertex_error);
  EXPECT_LT(errors[InterpolationMethod::edge].edge_length.p99, 0.3 * vertex_error);
  EXPECT_LT(errors[InterpolationMethod::mixit].edge_length.p99, 1.5 * errors[InterpolationMethod::edge].edge_length.p99);
  EXPECT_LT(errors[InterpolationMethod::mixit].dihedral_degrees.p99,
            1.5 * errors[InterpolationMethod::edge].dihedral_degrees.p99);
}

TEST(PoseInterpolator, FourPosesWithEqualWeights) {
  const PoseSet arm = demo_arm({30.0, 60.0, 90.0});
  const Eigen::VectorXd weights = Eigen::VectorXd::Constant(4, 0.25);
  PoseInterpolator mixit(arm);
  const Eigen::MatrixX3d x = mixit.interpolate(weights);
  ASSERT_TRUE(x.allFinite());
  PoseInterpolator edge(arm, with_method(InterpolationMethod::edge));
  const double edge_bend = arm_bend_degrees(arm, edge.interpolate(weights));
  EXPECT_NEAR(arm_bend_degrees(arm, x), edge_bend, 3.0);
  EXPECT_NEAR(edge_bend, 40.0, 6.0);
  const InterpolationError error = mixit.error(x, weights);
  EXPECT_EQ(error.collapsed_faces, 0);
  EXPECT_EQ(error.flipped_faces, 0);
  EXPECT_LT(error.edge_length.p99, 0.03);
}

TEST(PoseInterpolator, ARigidMotionKeepsTheShapeAndTurnsHalfway) {
  const PoseSet rest = demo_arm({}, 16);
  PoseSet poses(rest.faces());
  poses.add_pose(rest.pose(0));
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  poses.add_pose((rest.pose(0) * quarter.transpose()).rowwise() + Eigen::RowVector3d(2, 1, 0));
  for (const InterpolationMethod method : {InterpolationMethod::mixit, InterpolationMethod::edge}) {
    PoseInterpolator interpolator(poses, with_method(method));
    EXPECT_EQ(interpolator.layout().joints, 0) << to_string(method);
    const Eigen::MatrixX3d x = interpolator.interpolate(two_pose_weights(0.5));
    // The same shape, turned by 45 degrees about z, centred halfway.
    const RigidTransform fit = best_rigid_transform(rest.pose(0), x);
    EXPECT_LT(largest_distance(fit.apply(rest.pose(0)), x), 1e-6) << to_string(method);
    EXPECT_NEAR(Eigen::AngleAxisd(fit.rotation).angle(), 0.25 * 3.14159265358979323846, 1e-6) << to_string(method);
    const Eigen::RowVector3d centre = 0.5 * (poses.pose(0).colwise().mean() + poses.pose(1).colwise().mean());
    EXPECT_LT((x.colwise().mean() - centre).norm(), 1e-9) << to_string(method);
  }
}

TEST(PoseInterpolator, UserPartsAreUsed) {
  const PoseSet arm = demo_arm({90.0});
  InterpolationOptions options;
  options.face_parts.resize(arm.faces().rows());
  for (int f = 0; f < arm.faces().rows(); ++f) options.face_parts(f) = arm.pose(0)(arm.faces()(f, 0), 0) < 2.0 ? 4 : 9;
  PoseInterpolator interpolator(arm, options);
  EXPECT_EQ(interpolator.layout().parts, 2);
  EXPECT_EQ(interpolator.layout().joints, 1);
  EXPECT_EQ(interpolator.face_parts().maxCoeff(), 1);
  const Eigen::MatrixX3d x = interpolator.interpolate(two_pose_weights(0.5));
  EXPECT_NEAR(arm_bend_degrees(arm, x), 45.0, 6.0);
  options.face_parts.resize(5);
  EXPECT_THROW(PoseInterpolator(arm, options), ArgumentError);
}

TEST(PoseInterpolator, MeshesInSeveralPiecesAndStrayVertices) {
  // Two arms side by side, bent in opposite directions, plus a vertex that no face uses.
  const PoseSet one = demo_arm({90.0}, 16);
  const PoseSet other = demo_arm({-90.0}, 16);
  const int n = one.vertex_count();
  Eigen::MatrixX3i faces(2 * one.faces().rows(), 3);
  faces << one.faces(), one.faces().array() + n;
  PoseSet both(faces);
  for (int k = 0; k < 2; ++k) {
    Eigen::MatrixX3d x(2 * n + 1, 3);
    x << one.pose(k), other.pose(k).rowwise() + Eigen::RowVector3d(0, 0, 3), Eigen::RowVector3d(9, 9, k);
    both.add_pose(x);
  }
  for (const InterpolationMethod method : kMethods) {
    PoseInterpolator interpolator(both, with_method(method));
    const Eigen::MatrixX3d x = interpolator.interpolate(two_pose_weights(0.5));
    ASSERT_TRUE(x.allFinite()) << to_string(method);
    EXPECT_LT((x.row(2 * n) - Eigen::RowVector3d(9, 9, 0.5)).norm(), 1e-12) << to_string(method);
    // Each arm keeps its own place: the second stays about 3 units above the first.
    const double gap = x.block(n, 2, n, 1).mean() - x.block(0, 2, n, 1).mean();
    EXPECT_NEAR(gap, 3.0, 0.3) << to_string(method);
    const InterpolationError error = interpolator.error(x, two_pose_weights(0.5));
    if (method != InterpolationMethod::vertex) {
      EXPECT_LT(error.edge_length.p99, 0.06) << to_string(method);
    }
  }
}

TEST(PoseInterpolator, ChecksWeights) {
  const PoseSet arm = demo_arm({45.0});
  PoseInterpolator interpolator(arm, with_method(InterpolationMethod::vertex));
  EXPECT_THROW(interpolator.interpolate(Eigen::VectorXd::Constant(3, 1.0 / 3.0)), ArgumentError);
  EXPECT_THROW(interpolator.interpolate((Eigen::VectorXd(2) << 0.5, 0.6).finished()), ArgumentError);
  EXPECT_THROW(interpolator.interpolate((Eigen::VectorXd(2) << std::nan(""), 1.0).finished()), ArgumentError);
  // Within 1e-4 of 1 they are rescaled; extrapolation is allowed.
  const Eigen::MatrixX3d nearly = interpolator.interpolate((Eigen::VectorXd(2) << 0.50004, 0.50004).finished());
  EXPECT_LT(largest_distance(nearly, interpolator.interpolate(two_pose_weights(0.5))), 1e-12);
  EXPECT_TRUE(interpolator.interpolate(two_pose_weights(1.5)).allFinite());
  EXPECT_EQ(normalized_weights((Eigen::VectorXd(3) << 0.2, 0.3, 0.5).finished(), 3).sum(), 1.0);
}

TEST(PoseInterpolator, ChecksOptions) {
  const PoseSet arm = demo_arm({45.0});
  PoseSet one(arm.faces());
  one.add_pose(arm.pose(0));
  EXPECT_THROW(PoseInterpolator{one}, ArgumentError);
  const auto rejects = [&](auto change) {
    InterpolationOptions options;
    change(options);
    EXPECT_THROW(PoseInterpolator(arm, options), ArgumentError);
  };
  rejects([](InterpolationOptions& o) { o.joint_width = 0; });
  rejects([](InterpolationOptions& o) { o.refinement_iterations = -1; });
  rejects([](InterpolationOptions& o) { o.bending_weight = 0.0; });
  rejects([](InterpolationOptions& o) { o.segmentation.rigidity_angle_degrees = 200.0; });
  EXPECT_EQ(interpolation_method_from_string("edge"), InterpolationMethod::edge);
  EXPECT_THROW(interpolation_method_from_string("spline"), ArgumentError);
}

TEST(PoseInterpolator, OneShotFunctionReportsErrors) {
  const PoseSet arm = demo_arm({90.0});
  InterpolationReport report;
  const Eigen::MatrixX3d x = interpolate_poses(arm, two_pose_weights(0.5), InterpolationOptions{}, &report);
  EXPECT_TRUE(x.allFinite());
  EXPECT_GT(report.layout.joints, 0);
  EXPECT_GT(report.step.seconds.total, 0.0);
  EXPECT_TRUE(report.error.finite);
  EXPECT_GT(report.error.edge_length.max, 0.0);
}

}  // namespace
}  // namespace posekit::testing
