#include <gtest/gtest.h>

#include <posekit/blended_deformation.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/topology.hpp>

#include "blend_test_shapes.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace posekit {
namespace {

using testing::max_distortion;
using testing::small_arm;
using testing::spread_vertices;

std::vector<LinearConstraint> vertex_constraints(const std::vector<int>& vertices) {
  std::vector<LinearConstraint> constraints;
  for (int v : vertices) constraints.push_back(LinearConstraint::vertex(v));
  return constraints;
}

Eigen::MatrixX3d rows_of(const Eigen::MatrixX3d& pose, const std::vector<int>& vertices) {
  Eigen::MatrixX3d rows(static_cast<Eigen::Index>(vertices.size()), 3);
  for (size_t r = 0; r < vertices.size(); ++r) rows.row(static_cast<Eigen::Index>(r)) = pose.row(vertices[r]);
  return rows;
}

// Examples at 0, 45, 90 and 135 degrees; the targets are bends in between.
struct ArmDeformation : ::testing::Test {
  static void SetUpTestSuite() {
    examples = new PoseSet(small_arm({0.0, 45.0, 90.0, 135.0}));
    targets = new PoseSet(small_arm({0.0, 67.5, 112.5}));
    deformer = new BlendedDeformer(*examples);
  }
  static void TearDownTestSuite() {
    delete deformer;
    delete targets;
    delete examples;
  }
  static PoseSet* examples;
  static PoseSet* targets;
  static BlendedDeformer* deformer;
};
PoseSet* ArmDeformation::examples = nullptr;
PoseSet* ArmDeformation::targets = nullptr;
BlendedDeformer* ArmDeformation::deformer = nullptr;

TEST_F(ArmDeformation, PrecomputationReportsItsSizes) {
  const BlendSetupReport& r = deformer->setup_report();
  EXPECT_EQ(r.vertices, examples->vertex_count());
  EXPECT_EQ(r.examples, 4);
  EXPECT_EQ(r.weights, 20);
  EXPECT_EQ(r.full_atoms, 4 * 20 * 4);
  EXPECT_EQ(r.atoms, 160);
  EXPECT_EQ(r.clusters, 40);
  EXPECT_EQ(deformer->dictionary().atom_count(), 160);
}

TEST_F(ArmDeformation, ReconstructsAnUnseenBendFromTenPoints) {
  const std::vector<int> points = spread_vertices(targets->pose(1), 10);
  deformer->set_constraints(vertex_constraints(points));
  const BlendResult result = deformer->deform(rows_of(targets->pose(1), points));
  const double error = max_distortion(result.vertices, targets->pose(1), examples->faces());
  // The nearest examples (45 and 90 degrees) are far worse: their tips are off by a quarter turn.
  EXPECT_LT(error, 0.02);
  EXPECT_GT(max_distortion(examples->pose(1), targets->pose(1), examples->faces()), 10 * error);
  EXPECT_NEAR(result.scale, 1.0, 0.02);
  EXPECT_LT((rows_of(result.vertices, points) - rows_of(targets->pose(1), points)).cwiseAbs().maxCoeff(), 1e-3);
}

TEST_F(ArmDeformation, EnergyNeverRisesWithinAStage) {
  const std::vector<int> points = spread_vertices(targets->pose(2), 8);
  deformer->set_constraints(vertex_constraints(points));
  const BlendResult result = deformer->deform(rows_of(targets->pose(2), points));
  ASSERT_GE(result.iterations.size(), 3u);
  EXPECT_EQ(result.iterations.front().stage, "initial");
  for (size_t i = 1; i < result.iterations.size(); ++i) {
    const BlendIteration& a = result.iterations[i - 1];
    const BlendIteration& b = result.iterations[i];
    EXPECT_GE(b.energy, 0.0);
    if (a.stage == b.stage) {
      EXPECT_LE(b.energy, a.energy * (1 + 1e-9) + 1e-12) << i;
    }
  }
  EXPECT_EQ(result.iterations.back().stage, "minimal");
  EXPECT_EQ(result.energy, result.iterations.back().energy);
  // Bent at 112.5 degrees, between the examples at 90 and 135.
  EXPECT_TRUE(result.closest_example == 2 || result.closest_example == 3) << result.closest_example;
}

TEST_F(ArmDeformation, ChoosingTheExampleAfterItsSolveAlsoDescends) {
  BlendOptions after = deformer->options();
  after.example_choice_after_solve = true;
  BlendedDeformer exact(*examples, after);
  const std::vector<int> points = spread_vertices(targets->pose(1), 10);
  exact.set_constraints(vertex_constraints(points));
  const BlendResult result = exact.deform(rows_of(targets->pose(1), points));
  for (size_t i = 1; i < result.iterations.size(); ++i) {
    if (result.iterations[i].stage == "minimal" && result.iterations[i - 1].stage == "minimal") {
      EXPECT_LE(result.iterations[i].energy, result.iterations[i - 1].energy * (1 + 1e-9) + 1e-12) << i;
    }
  }
  EXPECT_LT(max_distortion(result.vertices, targets->pose(1), examples->faces()), 0.02);
  // Bent at 67.5 degrees, between the examples at 45 and 90.
  EXPECT_TRUE(result.closest_example == 1 || result.closest_example == 2) << result.closest_example;
}

TEST_F(ArmDeformation, RecoversTheScaleOfTheConstraints) {
  // The 90-degree example, 1.5 times larger and moved: the scale step finds 1.5.
  Eigen::MatrixX3d target = examples->pose(2) * 1.5;
  target.rowwise() += Eigen::RowVector3d(3.0, -1.0, 2.0);
  const std::vector<int> points = spread_vertices(target, 12);
  deformer->set_constraints(vertex_constraints(points));
  const BlendResult result = deformer->deform(rows_of(target, points));
  EXPECT_NEAR(result.scale, 1.5, 1e-3);
  EXPECT_LT(max_distortion(result.vertices, target, examples->faces()), 0.01);
}

TEST_F(ArmDeformation, ScalingTheConstraintsScalesTheResult) {
  // Every term of the energy is quadratic in (maps, targets, scale) together, and the affine maps
  // hold translations: constraints 1.5 times larger about any point give the result 1.5 times larger
  // about that point, and 1.5 times the scale, whatever the scale at the original size.
  const Eigen::MatrixX3d& target = targets->pose(2);
  const std::vector<int> points = spread_vertices(target, 10);
  deformer->set_constraints(vertex_constraints(points));
  const Eigen::RowVector3d center(0.7, -2.0, 1.1);
  const Eigen::MatrixX3d bigger = ((target.rowwise() - center) * 1.5).rowwise() + center;
  const BlendResult small = deformer->deform(rows_of(target, points));
  const BlendResult large = deformer->deform(rows_of(bigger, points));
  EXPECT_NEAR(large.scale / small.scale, 1.5, 1e-6);
  const Eigen::MatrixX3d expected = ((small.vertices.rowwise() - center) * 1.5).rowwise() + center;
  const double size = (target.colwise().maxCoeff() - target.colwise().minCoeff()).norm();
  EXPECT_LT((large.vertices - expected).cwiseAbs().maxCoeff(), 1e-6 * size);
}

TEST_F(ArmDeformation, WithoutTheScaleStepABiggerTargetIsFitWorse) {
  Eigen::MatrixX3d target = targets->pose(1) * 1.5;
  const std::vector<int> points = spread_vertices(target, 10);
  BlendOptions fixed = deformer->options();
  fixed.estimate_scale = false;
  BlendedDeformer unscaled(*examples, fixed);
  unscaled.set_constraints(vertex_constraints(points));
  deformer->set_constraints(vertex_constraints(points));
  const double with_scale = max_distortion(deformer->deform(rows_of(target, points)).vertices, target, examples->faces());
  const BlendResult without = unscaled.deform(rows_of(target, points));
  EXPECT_EQ(without.scale, 1.0);
  EXPECT_LT(2 * with_scale, max_distortion(without.vertices, target, examples->faces()));
}

TEST_F(ArmDeformation, FollowsARigidMotionOfTheConstraints) {
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::MatrixX3d target = (targets->pose(1) * turn.transpose()).rowwise() + Eigen::RowVector3d(-4, 5, 1);
  const std::vector<int> points = spread_vertices(target, 10);
  deformer->set_constraints(vertex_constraints(points));
  const BlendResult result = deformer->deform(rows_of(target, points));
  EXPECT_LT(max_distortion(result.vertices, target, examples->faces()), 0.02);
}

TEST_F(ArmDeformation, AllVerticesAsConstraintsReproduceAnExample) {
  std::vector<int> all(static_cast<size_t>(examples->vertex_count()));
  for (size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int>(v);
  deformer->set_constraints(vertex_constraints(all));
  const BlendResult result = deformer->deform(examples->pose(3));
  EXPECT_LT(max_distortion(result.vertices, examples->pose(3), examples->faces()), 1e-3);
  EXPECT_EQ(result.closest_example, 3);
}

TEST_F(ArmDeformation, ConstraintUpdatesMatchAFreshFactorization) {
  const std::vector<int> points = spread_vertices(targets->pose(2), 12);
  const Eigen::MatrixX3d positions = rows_of(targets->pose(2), points);
  // Start from the first 10, add two, remove one, replace one; then compare with set_constraints.
  deformer->set_constraints(vertex_constraints({points.begin(), points.begin() + 10}));
  deformer->add_constraint(LinearConstraint::vertex(points[10]));
  deformer->add_constraint(LinearConstraint::vertex(points[11]));
  deformer->remove_constraint(3);
  deformer->replace_constraint(0, LinearConstraint::vertex(points[3]));
  std::vector<int> expected(points.begin(), points.end());
  expected.erase(expected.begin() + 3);
  expected[0] = points[3];
  ASSERT_EQ(deformer->constraint_count(), 11);
  for (int r = 0; r < 11; ++r) EXPECT_EQ(deformer->constraints()[static_cast<size_t>(r)].vertices.front(), expected[r]);
  const Eigen::MatrixX3d targets_now = rows_of(targets->pose(2), expected);
  const BlendResult updated = deformer->deform(targets_now);
  deformer->set_constraints(vertex_constraints(expected));
  const BlendResult fresh = deformer->deform(targets_now);
  EXPECT_LT((updated.vertices - fresh.vertices).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_NEAR(updated.energy, fresh.energy, 1e-9 * fresh.energy);
  EXPECT_THROW(deformer->remove_constraint(11), ArgumentError);
  EXPECT_THROW(deformer->replace_constraint(-1, LinearConstraint::vertex(0)), ArgumentError);
}

TEST_F(ArmDeformation, WeightedAverageConstraintsWork) {
  // The centroid of each of three faces as a constraint: three vertices with coefficients 1/3.
  std::vector<LinearConstraint> constraints;
  Eigen::MatrixX3d positions(12, 3);
  const std::vector<int> points = spread_vertices(targets->pose(1), 12);
  const AdjacencyLists rings = vertex_neighbours(examples->faces(), examples->vertex_count());
  for (int r = 0; r < 12; ++r) {
    const int v = points[static_cast<size_t>(r)];
    LinearConstraint average{{v, rings[v][0], rings[v][1]}, {1.0 / 3, 1.0 / 3, 1.0 / 3}, 1.0};
    positions.row(r) = (targets->pose(1).row(v) + targets->pose(1).row(rings[v][0]) + targets->pose(1).row(rings[v][1])) / 3;
    constraints.push_back(average);
  }
  deformer->set_constraints(constraints);
  const BlendResult result = deformer->deform(positions);
  EXPECT_LT(max_distortion(result.vertices, targets->pose(1), examples->faces()), 0.02);
}

TEST_F(ArmDeformation, InterpolationStartsAndEndsAtTheTwoDeformations) {
  const std::vector<int> points = spread_vertices(targets->pose(1), 10);
  deformer->set_constraints(vertex_constraints(points));
  const BlendResult a = deformer->deform(rows_of(targets->pose(1), points));
  const BlendResult b = deformer->deform(rows_of(targets->pose(2), points));
  EXPECT_LT((deformer->interpolate(a, b, 0.0) - a.vertices).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((deformer->interpolate(a, b, 1.0) - b.vertices).cwiseAbs().maxCoeff(), 1e-9);
  // Half way between 67.5 and 112.5 degrees: near the 90-degree pose, and nearer than the average of
  // the two results, which shortens the arm. (The constraint targets themselves move on straight
  // lines, which pulls the tips in a little.)
  const Eigen::MatrixX3d middle = deformer->interpolate(a, b, 0.5);
  const double error = max_distortion(middle, examples->pose(2), examples->faces());
  EXPECT_LT(error, 0.06);
  EXPECT_LT(2 * error, max_distortion(0.5 * (a.vertices + b.vertices), examples->pose(2), examples->faces()));
  EXPECT_THROW(deformer->interpolate(a, b, 1.5), ArgumentError);
}

TEST_F(ArmDeformation, ContinuesFromAStart) {
  const std::vector<int> points = spread_vertices(targets->pose(1), 10);
  deformer->set_constraints(vertex_constraints(points));
  const Eigen::MatrixX3d positions = rows_of(targets->pose(1), points);
  const BlendResult first = deformer->deform(positions);
  const BlendResult again = deformer->deform(positions, first);
  EXPECT_LE(again.energy, first.energy * (1 + 1e-9));
  EXPECT_LT(max_distortion(again.vertices, first.vertices, examples->faces()), 2e-3);
}

TEST_F(ArmDeformation, ElasticNetGivesSparserInitialMaps) {
  const std::vector<int> points = spread_vertices(targets->pose(1), 10);
  const Eigen::MatrixX3d positions = rows_of(targets->pose(1), points);
  BlendOptions options = deformer->options();
  options.average_iterations = 0;
  options.minimal_iterations = 0;
  BlendedDeformer plain(*examples, options);
  options.sparsity = 0.05;
  BlendedDeformer sparse(*examples, options);
  plain.set_constraints(vertex_constraints(points));
  sparse.set_constraints(vertex_constraints(points));
  const BlendResult a = plain.deform(positions);
  const BlendResult b = sparse.deform(positions);
  const auto zero_rows = [](const Eigen::MatrixX3d& t) { return (t.rowwise().squaredNorm().array() == 0.0).count(); };
  EXPECT_EQ(zero_rows(a.transformations), 0);
  EXPECT_GT(zero_rows(b.transformations), b.transformations.rows() / 2);
  // The iterations from the sparse start (which meets the constraints less closely than the plain
  // one) reach a good pose too, given a few more of them.
  BlendOptions full = deformer->options();
  full.sparsity = 0.05;
  full.average_iterations = 8;
  BlendedDeformer iterated(*examples, full);
  iterated.set_constraints(vertex_constraints(points));
  EXPECT_LT(max_distortion(iterated.deform(positions).vertices, targets->pose(1), examples->faces()), 0.03);
}

TEST_F(ArmDeformation, RejectsBadConstraintsAndTargets) {
  const int n = examples->vertex_count();
  EXPECT_THROW(deformer->set_constraints({}), ArgumentError);
  EXPECT_THROW(deformer->set_constraints({LinearConstraint::vertex(n)}), ArgumentError);
  EXPECT_THROW(deformer->set_constraints({LinearConstraint::vertex(-1)}), ArgumentError);
  EXPECT_THROW(deformer->set_constraints({LinearConstraint{{0, 1}, {0.5}, 1.0}}), ArgumentError);
  EXPECT_THROW(deformer->set_constraints({LinearConstraint::vertex(0, 0.0)}), ArgumentError);
  deformer->set_constraints(vertex_constraints({0, 1, 2}));
  EXPECT_THROW(deformer->deform(Eigen::MatrixX3d::Zero(2, 3)), ArgumentError);
  Eigen::MatrixX3d bad = Eigen::MatrixX3d::Zero(3, 3);
  bad(1, 2) = std::numeric_limits<double>::quiet_NaN();
  try {
    deformer->deform(bad);
    FAIL() << "a NaN target was accepted";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("constraint 1"), std::string::npos) << error.what();
  }
}

TEST(BlendedDeformer, RejectsADegenerateReferenceAndBadOptions) {
  PoseSet arm = small_arm({0.0, 90.0});
  Eigen::MatrixX3d flat = arm.pose(0);
  const Eigen::RowVector3i face = arm.faces().row(5);
  flat.row(face(2)) = flat.row(face(0));
  PoseSet degenerate(arm.faces());
  degenerate.add_pose(flat);
  degenerate.add_pose(arm.pose(1));
  try {
    BlendedDeformer d(degenerate);
    FAIL() << "a degenerate reference was accepted";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("reference"), std::string::npos) << error.what();
  }
  EXPECT_THROW(BlendedDeformer(PoseSet(arm.faces())), ArgumentError);
  BlendOptions o;
  o.atom_fraction = 0.0;
  EXPECT_THROW(BlendedDeformer(arm, o), ArgumentError);
  o = {};
  o.eigenfunctions = arm.vertex_count();
  EXPECT_THROW(BlendedDeformer(arm, o), ArgumentError);
  o = {};
  o.sparsity = 1.0;
  EXPECT_THROW(BlendedDeformer(arm, o), ArgumentError);
  EXPECT_THROW(BlendedDeformer(arm, Eigen::MatrixXd::Ones(3, 2)), ArgumentError);
}

TEST(BlendedDeformer, SkinningWeightsWithOneClusterPerBone) {
  // Two bones blended linearly over the joint, as the demo arm was generated.
  const PoseSet examples = small_arm({0.0, 45.0, 135.0});
  const PoseSet target = small_arm({90.0});
  Eigen::MatrixXd weights(examples.vertex_count(), 2);
  for (int v = 0; v < examples.vertex_count(); ++v) {
    const double s = std::clamp((examples.pose(0)(v, 0) - 1.5) / 1.0, 0.0, 1.0);
    weights.row(v) << 1.0 - s, s;
  }
  BlendOptions options;
  options.rotation_clusters = 0;
  options.atom_fraction = 1.0;
  BlendedDeformer deformer(examples, weights, options);
  EXPECT_EQ(deformer.cluster_count(), 2);
  EXPECT_EQ(deformer.setup_report().weights, 2);
  const std::vector<int> points = spread_vertices(target.pose(0), 10);
  deformer.set_constraints(vertex_constraints(points));
  const BlendResult result = deformer.deform(rows_of(target.pose(0), points));
  EXPECT_LT(max_distortion(result.vertices, target.pose(0), examples.faces()), 0.02);
}

TEST(BlendedDeformer, WorksWithASingleExample) {
  const PoseSet one = small_arm({0.0});
  const PoseSet target = small_arm({45.0});
  BlendedDeformer deformer(one);
  const std::vector<int> points = spread_vertices(target.pose(0), 12);
  deformer.set_constraints(vertex_constraints(points));
  const BlendResult result = deformer.deform(rows_of(target.pose(0), points));
  EXPECT_EQ(result.closest_example, 0);
  EXPECT_LT(max_distortion(result.vertices, target.pose(0), one.faces()), 0.05);
}

}  // namespace
}  // namespace posekit
