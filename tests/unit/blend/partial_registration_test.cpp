#include <gtest/gtest.h>

#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/partial_registration.hpp>

#include "blend_test_shapes.hpp"

#include <Eigen/Geometry>

namespace posekit {
namespace {

// The 60-degree bend (not an example), turned and moved, with the far half of its second bone and
// a strip along the first cut away.
struct ArmScan : ::testing::Test {
  void SetUp() override {
    examples = testing::small_arm({0.0, 45.0, 90.0, 135.0});
    const PoseSet bent = testing::small_arm({60.0});
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0, 0, 1)).toRotationMatrix();
    truth = (bent.pose(0) * turn.transpose()).rowwise() + Eigen::RowVector3d(0.3, -0.2, 0.5);
    const Eigen::MatrixX3d& rest = examples.pose(0);
    const Eigen::MatrixX3i& faces = examples.faces();
    scan = testing::partial_scan(
        truth, faces,
        [&](int f) {
          const Eigen::RowVector3d c = (rest.row(faces(f, 0)) + rest.row(faces(f, 1)) + rest.row(faces(f, 2))) / 3;
          return c(0) < 3.2 && !(c(0) > 0.5 && c(0) < 1.5 && c(2) > 0.2);
        },
        original);
    for (int v : testing::spread_vertices(scan.vertices, 6)) features.push_back(original[static_cast<size_t>(v)]);
    positions.resize(6, 3);
    for (int r = 0; r < 6; ++r) positions.row(r) = truth.row(features[static_cast<size_t>(r)]);
  }
  PoseSet examples;
  Eigen::MatrixX3d truth;
  Mesh scan;
  std::vector<int> original;
  std::vector<int> features;
  Eigen::MatrixX3d positions;
};

TEST_F(ArmScan, CompletesTheMeshAndMatchesTheScan) {
  BlendedDeformer deformer(examples);
  const ScanRegistration r = register_partial_scan(deformer, scan, features, positions);
  ASSERT_EQ(r.iterations.size(), 10u);
  EXPECT_GT(r.iterations.back().matches, scan.vertices.rows() / 2);
  const double initial = testing::max_distortion(r.initial.vertices, truth, examples.faces());
  const double final_error = testing::max_distortion(r.deformation.vertices, truth, examples.faces());
  EXPECT_LT(final_error, 0.03);
  EXPECT_LE(final_error, initial);
  EXPECT_GT(r.feature_discs, 20);
  // Every scan vertex is matched to a mesh vertex within 5 % of the square root of the area of its
  // true position.
  const double length = std::sqrt(face_areas(truth, examples.faces()).sum());
  ASSERT_EQ(r.correspondence.size(), scan.vertices.rows());
  int good = 0;
  for (Eigen::Index i = 0; i < scan.vertices.rows(); ++i) {
    good += (truth.row(r.correspondence(i)) - truth.row(original[static_cast<size_t>(i)])).norm() < 0.05 * length;
  }
  EXPECT_GT(good, 0.98 * scan.vertices.rows());
  EXPECT_LT(r.distances.maxCoeff(), 0.05 * length);
}

TEST_F(ArmScan, FeaturePointsAloneAlsoWork) {
  BlendedDeformer deformer(examples);
  ScanFitOptions options;
  options.feature_rings = 0;
  const ScanRegistration r = register_partial_scan(deformer, scan, features, positions, options);
  EXPECT_EQ(r.feature_discs, 0);
  EXPECT_LT(testing::max_distortion(r.deformation.vertices, truth, examples.faces()), 0.02);
}

TEST_F(ArmScan, DiscCentroidsAreMetByTheTruePose) {
  BlendedDeformer deformer(examples);
  const FeatureConstraints fixed = feature_constraints(deformer, scan, features, positions);
  ASSERT_EQ(fixed.constraints.size(), features.size() + static_cast<size_t>(fixed.discs));
  const double length = std::sqrt(face_areas(truth, examples.faces()).sum());
  for (size_t r = 0; r < fixed.constraints.size(); ++r) {
    const LinearConstraint& c = fixed.constraints[r];
    double sum = 0.0;
    Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
    for (size_t i = 0; i < c.vertices.size(); ++i) {
      x += c.coefficients[i] * truth.row(c.vertices[i]);
      sum += c.coefficients[i];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    // Exact but for the arm's stretch near its joint, which the reference (straight) does not have.
    EXPECT_LT((x - fixed.targets.row(static_cast<Eigen::Index>(r))).norm(), 0.01 * length) << r;
  }
}

TEST_F(ArmScan, RejectsBadInput) {
  BlendedDeformer deformer(examples);
  EXPECT_THROW(register_partial_scan(deformer, Mesh{}, features, positions), ArgumentError);
  EXPECT_THROW(register_partial_scan(deformer, scan, {}, Eigen::MatrixX3d(0, 3)), ArgumentError);
  EXPECT_THROW(register_partial_scan(deformer, scan, {1, 2}, positions), ArgumentError);
  std::vector<int> outside = features;
  outside[0] = examples.vertex_count();
  EXPECT_THROW(register_partial_scan(deformer, scan, outside, positions), ArgumentError);
  ScanFitOptions options;
  options.scan_weight = 0.0;
  EXPECT_THROW(register_partial_scan(deformer, scan, features, positions, options), ArgumentError);
}

}  // namespace
}  // namespace posekit
