#include <gtest/gtest.h>

#include <posekit/blend_files.hpp>
#include <posekit/blended_deformation.hpp>
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/skinning_decomposition.hpp>

#include "blend_test_shapes.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace posekit {
namespace {

using testing::small_arm;

// The arm bent about its joint (x = 2, y = 0): two rigid parts blended over the joint.
struct ArmSkinning : ::testing::Test {
  static void SetUpTestSuite() {
    examples = new PoseSet(small_arm({0.0, 30.0, 60.0, 90.0, 120.0}));
    decomposition = new SkinningDecomposition(decompose_skinning(*examples));
  }
  static void TearDownTestSuite() {
    delete decomposition;
    delete examples;
  }
  static PoseSet* examples;
  static SkinningDecomposition* decomposition;
};
PoseSet* ArmSkinning::examples = nullptr;
SkinningDecomposition* ArmSkinning::decomposition = nullptr;

TEST_F(ArmSkinning, WeightsAreNonNegativeSparseAndSumToOne) {
  const SkinningDecomposition& d = *decomposition;
  EXPECT_NO_THROW(check_skinning_decomposition(d));
  EXPECT_EQ(d.vertex_count(), examples->vertex_count());
  EXPECT_EQ(d.example_count(), examples->pose_count());
  EXPECT_GE(d.bone_count(), 2);
  EXPECT_LE(d.bone_count(), SkinningOptions{}.max_bones);
  EXPECT_GE(d.weights.minCoeff(), 0.0);
  for (int i = 0; i < d.vertex_count(); ++i) {
    EXPECT_NEAR(d.weights.row(i).sum(), 1.0, 1e-9);
    EXPECT_LE((d.weights.row(i).array() > 0.0).count(), SkinningOptions{}.influences);
  }
}

TEST_F(ArmSkinning, SkinningRebuildsTheExamples) {
  const SkinningDecomposition& d = *decomposition;
  const double diagonal = bounding_box_diagonal(examples->pose(0));
  double squared = 0.0;
  for (int k = 1; k < examples->pose_count(); ++k) {
    const Eigen::MatrixX3d rebuilt = skinned_pose(d, examples->pose(0), k);
    squared += (rebuilt - examples->pose(k)).rowwise().squaredNorm().sum();
  }
  const double rms = std::sqrt(squared / (d.vertex_count() * (examples->pose_count() - 1))) / diagonal;
  EXPECT_NEAR(rms, d.rms_error, 1e-9);
  // The arm is made by linear blend skinning of two bones: the learned skinning fits it closely.
  EXPECT_LT(d.rms_error, 0.003);
  EXPECT_LT(d.max_error, 0.03);
  // The reference is its own skinning.
  EXPECT_LT((skinned_pose(d, examples->pose(0), 0) - examples->pose(0)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST_F(ArmSkinning, TheSkeletonIsATreeWithAJointNearTheElbow) {
  const SkinningDecomposition& d = *decomposition;
  EXPECT_EQ(std::count(d.parents.begin(), d.parents.end(), -1), 1);  // one connected mesh, one root
  // Some joint lies at the bend axis (x = 2, y = 0, along z): the two halves turn about it.
  double nearest = std::numeric_limits<double>::infinity();
  for (int j = 0; j < d.bone_count(); ++j) {
    if (d.parents[static_cast<size_t>(j)] < 0) continue;
    nearest = std::min(nearest, std::hypot(d.joints(j, 0) - 2.0, d.joints(j, 1)));
  }
  EXPECT_LT(nearest, 0.25);
}

TEST_F(ArmSkinning, AChosenBoneCountIsAnUpperBound) {
  SkinningOptions options;
  options.bones = 1;
  EXPECT_EQ(decompose_skinning(*examples, options).bone_count(), 1);
  // The arm has two rigid parts: a third bone finds nothing of its own and is removed.
  options.bones = 3;
  const SkinningDecomposition d = decompose_skinning(*examples, options);
  EXPECT_GE(d.bone_count(), 2);
  EXPECT_LE(d.bone_count(), 3);
  EXPECT_NO_THROW(check_skinning_decomposition(d));
  EXPECT_LT(d.rms_error, 0.01);
}

TEST_F(ArmSkinning, IsDeterministic) {
  const SkinningDecomposition again = decompose_skinning(*examples);
  EXPECT_EQ(again.weights, decomposition->weights);
  EXPECT_EQ(again.parents, decomposition->parents);
}

TEST(SkinningDecomposition, ARigidMotionIsOneBone) {
  const PoseSet arm = small_arm({0.0});
  PoseSet examples(arm.faces());
  examples.add_pose(arm.pose(0));
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  examples.add_pose((arm.pose(0) * turn.transpose()).rowwise() + Eigen::RowVector3d(3, -1, 2));
  const SkinningDecomposition d = decompose_skinning(examples);
  EXPECT_EQ(d.bone_count(), 1);
  EXPECT_LT(d.rms_error, 1e-9);
  EXPECT_LT((d.motions[1][0].rotation - turn).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(SkinningDecomposition, RejectsBadInput) {
  const PoseSet arm = small_arm({0.0, 60.0});
  PoseSet one(arm.faces());
  one.add_pose(arm.pose(0));
  EXPECT_THROW(decompose_skinning(one), ArgumentError);
  SkinningOptions options;
  options.bones = arm.vertex_count() + 1;
  EXPECT_THROW(decompose_skinning(arm, options), ArgumentError);
  options = {};
  options.influences = 0;
  EXPECT_THROW(decompose_skinning(arm, options), ArgumentError);
  options = {};
  options.smoothness = -1.0;
  EXPECT_THROW(decompose_skinning(arm, options), ArgumentError);
  PoseSet bad(arm.faces());
  bad.add_pose(arm.pose(0));
  Eigen::MatrixX3d broken = arm.pose(1);
  broken(3, 1) = std::nan("");
  bad.add_pose(broken);
  EXPECT_THROW(decompose_skinning(bad), ArgumentError);
}

TEST(SkinningDecomposition, CheckRefusesBrokenDecompositions) {
  const SkinningDecomposition good = decompose_skinning(small_arm({0.0, 60.0, 120.0}));
  SkinningDecomposition d = good;
  d.weights(0, 0) += 0.5;
  EXPECT_THROW(check_skinning_decomposition(d), ArgumentError);
  d = good;
  d.parents.assign(d.parents.size(), 0);  // bone 0 its own parent: a cycle
  EXPECT_THROW(check_skinning_decomposition(d), ArgumentError);
  d = good;
  d.motions.pop_back();
  d.motions.pop_back();
  EXPECT_THROW(check_skinning_decomposition(d), ArgumentError);
}

// ---- The cache ----

struct SkinningCache : ArmSkinning {
  std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "posekit-skinning-cache-test.txt";
  void TearDown() override { std::filesystem::remove(file); }
};

TEST_F(SkinningCache, RoundTrips) {
  write_skinning_decomposition(file, *decomposition, *examples);
  const SkinningDecomposition read = read_skinning_decomposition(file, *examples);
  EXPECT_EQ(read.weights, decomposition->weights);
  EXPECT_EQ(read.parents, decomposition->parents);
  EXPECT_EQ(read.joints, decomposition->joints);
  EXPECT_EQ(read.rms_error, decomposition->rms_error);
  for (int k = 0; k < read.example_count(); ++k) {
    for (int j = 0; j < read.bone_count(); ++j) {
      EXPECT_EQ(read.motions[k][j].rotation, decomposition->motions[k][j].rotation);
      EXPECT_EQ(read.motions[k][j].translation, decomposition->motions[k][j].translation);
    }
  }
}

std::string message_of(const std::function<void()>& body) {
  try {
    body();
  } catch (const InputError& error) {
    return error.what();
  }
  return "no InputError";
}

TEST_F(SkinningCache, RefusesAnotherMeshOrOtherExamples) {
  write_skinning_decomposition(file, *decomposition, *examples);
  DemoArmOptions finer;
  finer.ring_segments = 24;
  finer.bend_angles_degrees = {30.0, 60.0, 90.0, 120.0};
  const PoseSet other_mesh = make_demo_arm(finer);
  const std::string mesh_message = message_of([&] { read_skinning_decomposition(file, other_mesh); });
  EXPECT_NE(mesh_message.find(file.string()), std::string::npos) << mesh_message;
  EXPECT_NE(mesh_message.find("for a mesh of"), std::string::npos) << mesh_message;

  const PoseSet other_poses = small_arm({0.0, 20.0, 60.0, 90.0, 120.0});
  const std::string poses_message = message_of([&] { read_skinning_decomposition(file, other_poses); });
  EXPECT_NE(poses_message.find("other example poses"), std::string::npos) << poses_message;
}

TEST_F(SkinningCache, RefusesAMalformedFileWithItsLine) {
  write_skinning_decomposition(file, *decomposition, *examples);
  std::string text;
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const size_t weights = text.find("\nweights 5 ");
  ASSERT_NE(weights, std::string::npos);
  text.insert(weights + 11, "x");
  {
    std::ofstream out(file, std::ios::trunc);
    out << text;
  }
  const std::string message = message_of([&] { read_skinning_decomposition(file, *examples); });
  EXPECT_NE(message.find(file.string() + ":"), std::string::npos) << message;
  EXPECT_NE(message.find("is not a bone index"), std::string::npos) << message;
  EXPECT_NE(message_of([&] { read_skinning_decomposition(file.string() + "-missing", *examples); }).find("cannot open"),
            std::string::npos);
}

// ---- The skeleton dictionary ----

TEST_F(ArmSkinning, TheSkeletonDictionaryFollowsTheLaplaceBeltramiStages) {
  BlendOptions options;
  options.dictionary = DictionaryChoice::skeleton;
  BlendedDeformer deformer(*examples, *decomposition, options);
  const BlendSetupReport& report = deformer.setup_report();
  EXPECT_EQ(report.dictionary, "skeleton");
  EXPECT_EQ(report.bones, decomposition->bone_count());
  // The bones beside the 20 eigenfunctions, unless the paper's bones-alone form is asked for.
  EXPECT_EQ(report.weights, decomposition->bone_count() + options.eigenfunctions);
  BlendOptions bones_alone = options;
  bones_alone.skeleton_keeps_eigenfunctions = false;
  EXPECT_EQ(BlendedDeformer(*examples, *decomposition, bones_alone).setup_report().weights, decomposition->bone_count());
  EXPECT_EQ(deformer.cluster_count(), decomposition->bone_count());  // one rotation cluster per bone
  ASSERT_NE(deformer.skinning(), nullptr);

  const PoseSet target = small_arm({0.0, 75.0});
  const std::vector<int> points = testing::spread_vertices(target.pose(1), 12);
  std::vector<LinearConstraint> constraints;
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t r = 0; r < points.size(); ++r) {
    constraints.push_back(LinearConstraint::vertex(points[r]));
    positions.row(static_cast<Eigen::Index>(r)) = target.pose(1).row(points[r]);
  }
  deformer.set_constraints(constraints);
  const BlendResult result = deformer.deform(positions);
  // The stages in order: Laplace-Beltrami first, then the skeleton dictionary.
  ASSERT_FALSE(result.iterations.empty());
  EXPECT_EQ(result.iterations.front().stage, "initial");
  EXPECT_EQ(result.iterations.back().stage.rfind("skeleton ", 0), 0u);
  EXPECT_EQ(result.transformations.rows(), deformer.dictionary().atom_count());
  EXPECT_LT(testing::max_distortion(result.vertices, target.pose(1), examples->faces()), 0.03);
  // Interpolation and continuation stay in the skeleton dictionary.
  const BlendResult again = deformer.deform(positions, result, 0, 2);
  EXPECT_EQ(again.transformations.rows(), result.transformations.rows());
  EXPECT_LT((deformer.interpolate(result, again, 0.0) - result.vertices).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(SkeletonDictionary, AutomaticChoosesTheDictionaryThatRebuildsHeldOutExamplesBetter) {
  BlendOptions options;
  options.dictionary = DictionaryChoice::automatic;
  const BlendedDeformer arm(small_arm({0.0, 30.0, 60.0, 90.0, 120.0}), options);
  const BlendSetupReport& r = arm.setup_report();
  EXPECT_EQ(r.trial.examples, 2);
  EXPECT_GT(r.trial.lbo, 0.0);
  EXPECT_GT(r.trial.skeleton, 0.0);
  EXPECT_EQ(r.dictionary, r.trial.skeleton < r.trial.lbo ? "skeleton" : "lbo");
  EXPECT_EQ(arm.skinning() != nullptr, r.dictionary == "skeleton");

  // A sphere whose examples swell and dent smoothly: no rigid parts, and the trial says so.
  const Mesh sphere = testing::icosphere(3);
  PoseSet waves(sphere.faces);
  waves.add_pose(sphere.vertices);
  for (int k = 1; k <= 4; ++k) {
    Eigen::MatrixX3d pose = sphere.vertices;
    for (Eigen::Index i = 0; i < pose.rows(); ++i) {
      const Eigen::RowVector3d x = sphere.vertices.row(i);
      pose.row(i) = x * (1.0 + 0.25 * std::sin(3.0 * k * x(0) + 2.0 * x(1) - k * x(2)));
    }
    waves.add_pose(pose);
  }
  const BlendedDeformer smooth(waves, options);
  EXPECT_EQ(smooth.setup_report().trial.examples, 2);
  EXPECT_EQ(smooth.setup_report().dictionary,
            smooth.setup_report().trial.skeleton < smooth.setup_report().trial.lbo ? "skeleton" : "lbo");

  // Two examples leave nothing to hold out: the Laplace-Beltrami dictionary, without a trial.
  const BlendedDeformer two(small_arm({0.0, 90.0}), options);
  EXPECT_EQ(two.setup_report().trial.examples, 0);
  EXPECT_EQ(two.setup_report().dictionary, "lbo");
}

TEST(SkeletonDictionary, RejectsADecompositionOfOtherExamples) {
  const PoseSet examples = small_arm({0.0, 45.0, 90.0});
  const SkinningDecomposition fewer = decompose_skinning(small_arm({0.0, 90.0}));
  BlendOptions options;
  options.dictionary = DictionaryChoice::skeleton;
  EXPECT_THROW(BlendedDeformer(examples, fewer, options), ArgumentError);
  EXPECT_THROW(BlendedDeformer(examples, Eigen::MatrixXd::Ones(examples.vertex_count(), 1), options), ArgumentError);
}

}  // namespace
}  // namespace posekit
