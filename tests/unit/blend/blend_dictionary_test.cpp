#include <gtest/gtest.h>

#include <posekit/blend_dictionary.hpp>
#include <posekit/error.hpp>
#include <posekit/laplace_beltrami.hpp>

#include "blend_test_shapes.hpp"
#include "test_data.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>

namespace posekit {
namespace {

struct ArmDictionary : ::testing::Test {
  void SetUp() override {
    arm = testing::small_arm({0.0, 45.0, 90.0});
    // Each example turned differently, so that no coordinate is shared between examples (the arm
    // bends in its xy plane and would keep z).
    for (int k = 0; k < arm.pose_count(); ++k) {
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.3 * (k + 1), Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
      examples.push_back(arm.pose(k) * turn.transpose());
    }
    weights = laplace_beltrami_basis(examples[0], arm.faces(), 5).eigenfunctions;
    mass = lumped_mass(examples[0], arm.faces());
  }
  PoseSet arm;
  std::vector<Eigen::MatrixX3d> examples;
  Eigen::MatrixXd weights;
  Eigen::VectorXd mass;
};

// Largest distance from a column of `a` to the span of `b`, relative to that column.
double span_residual(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(b);
  double worst = 0.0;
  for (Eigen::Index c = 0; c < a.cols(); ++c) {
    const Eigen::VectorXd x = qr.solve(a.col(c));
    worst = std::max(worst, (b * x - a.col(c)).norm() / a.col(c).norm());
  }
  return worst;
}

TEST_F(ArmDictionary, FullDictionaryHasFourAtomsPerWeightAndExample) {
  const BlendDictionary d(examples, weights);
  EXPECT_EQ(d.atom_count(), 4 * 5 * 3);
  const Eigen::MatrixXd m = d.matrix();
  for (int p = 0; p < d.atom_count(); ++p) {
    const DictionaryAtom& a = d.atoms()[static_cast<size_t>(p)];
    const Eigen::VectorXd expected = a.coordinate == 3 ? Eigen::VectorXd(weights.col(a.weight))
                                                       : Eigen::VectorXd(weights.col(a.weight).cwiseProduct(
                                                             examples[static_cast<size_t>(a.example)].col(a.coordinate)));
    EXPECT_LT((m.col(p) - expected).cwiseAbs().maxCoeff(), 1e-14) << p;
  }
  EXPECT_TRUE(testing::matrices_near(d.rows({3, 7}), Eigen::MatrixXd(m(std::vector<int>{3, 7}, Eigen::all)), 0, 0));
}

TEST_F(ArmDictionary, ReproducesEachExampleExactly) {
  const BlendDictionary d(examples, weights);
  for (int k = 0; k < 3; ++k) {
    const Eigen::MatrixX3d x = d.matrix() * d.example_transformations(k);
    EXPECT_LT((x - examples[static_cast<size_t>(k)]).cwiseAbs().maxCoeff(), 1e-10) << k;
  }
}

TEST_F(ArmDictionary, SmoothnessCouplesOnlyAtomsOfOneExampleAndCoordinate) {
  const BlendDictionary d(examples, weights);
  Eigen::MatrixXd s = Eigen::MatrixXd::Random(5, 5);
  s = (s * s.transpose()).eval();
  const Eigen::MatrixXd lambda = d.transformation_smoothness(s);
  for (int p = 0; p < d.atom_count(); ++p) {
    for (int q = 0; q < d.atom_count(); ++q) {
      const DictionaryAtom& a = d.atoms()[static_cast<size_t>(p)];
      const DictionaryAtom& b = d.atoms()[static_cast<size_t>(q)];
      const double expected = a.example == b.example && a.coordinate == b.coordinate ? s(a.weight, b.weight) : 0.0;
      EXPECT_EQ(lambda(p, q), expected);
    }
  }
  EXPECT_THROW(d.transformation_smoothness(Eigen::MatrixXd::Identity(4, 4)), ArgumentError);
}

TEST_F(ArmDictionary, ReductionDropsDuplicateAtomsFirst) {
  // The constant-coordinate atoms w_j * 1 are the same for every example: 2 of each 3 are duplicates.
  const BlendDictionary full(examples, weights);
  const int distinct = full.atom_count() - 2 * 5;
  const BlendDictionary reduced = reduce_dictionary(full, distinct, mass);
  ASSERT_EQ(reduced.atom_count(), distinct);
  int homogeneous = 0;
  for (const DictionaryAtom& a : reduced.atoms()) homogeneous += a.coordinate == 3;
  EXPECT_EQ(homogeneous, 5);
  EXPECT_LT(span_residual(full.matrix(), reduced.matrix()), 1e-8);
}

TEST_F(ArmDictionary, ReductionKeepsOriginalAtomsAndIsDeterministic) {
  const BlendDictionary full(examples, weights);
  const BlendDictionary a = reduce_dictionary(full, 20, mass);
  const BlendDictionary b = reduce_dictionary(full, 20, mass);
  ASSERT_EQ(a.atom_count(), 20);
  EXPECT_EQ(a.atoms(), b.atoms());
  for (const DictionaryAtom& atom : a.atoms()) {
    EXPECT_NE(std::find(full.atoms().begin(), full.atoms().end(), atom), full.atoms().end());
  }
  EXPECT_EQ(reduce_dictionary(full, 1000, mass).atom_count(), full.atom_count());
  EXPECT_THROW(reduce_dictionary(full, 0, mass), ArgumentError);
}

TEST_F(ArmDictionary, ChangeToARicherDictionaryKeepsThePose) {
  const BlendDictionary full(examples, weights);
  const BlendDictionary reduced = reduce_dictionary(full, 30, mass);
  Eigen::MatrixX3d t = Eigen::MatrixX3d::Random(reduced.atom_count(), 3);
  const Eigen::MatrixX3d pose = reduced.matrix() * t;
  const DictionaryChange change(reduced, full, mass);
  const Eigen::MatrixX3d carried = full.matrix() * change(t);
  EXPECT_LT((carried - pose).cwiseAbs().maxCoeff(), 1e-6 * pose.cwiseAbs().maxCoeff());
}

TEST_F(ArmDictionary, ChangeToAPoorerDictionaryIsTheLeastSquaresFit) {
  const BlendDictionary full(examples, weights);
  const BlendDictionary reduced = reduce_dictionary(full, 20, mass);
  const Eigen::MatrixX3d pose = examples[2];
  const Eigen::MatrixX3d t = full.example_transformations(2);
  const DictionaryChange change(full, reduced, mass);
  const Eigen::MatrixX3d fitted = change(t);
  const auto error = [&](const Eigen::MatrixX3d& x) {
    return (mass.asDiagonal() * (reduced.matrix() * x - pose).cwiseAbs2()).sum();
  };
  const double best = error(fitted);
  for (int trial = 0; trial < 5; ++trial) {
    EXPECT_LE(best, error(fitted + 1e-3 * Eigen::MatrixX3d::Random(fitted.rows(), 3)) + 1e-12);
  }
}

TEST(BlendDictionary, RejectsBadInput) {
  EXPECT_THROW(BlendDictionary({}, Eigen::MatrixXd::Ones(3, 1)), ArgumentError);
  EXPECT_THROW(BlendDictionary({Eigen::MatrixX3d::Zero(4, 3)}, Eigen::MatrixXd::Ones(3, 1)), ArgumentError);
  EXPECT_THROW(BlendDictionary({Eigen::MatrixX3d::Zero(3, 3)}, Eigen::MatrixXd::Ones(3, 1), {{1, 0, 0}}), ArgumentError);
  EXPECT_THROW(BlendDictionary({Eigen::MatrixX3d::Zero(3, 3)}, Eigen::MatrixXd::Ones(3, 1), {{0, 0, 4}}), ArgumentError);
  const BlendDictionary d({Eigen::MatrixX3d::Zero(3, 3)}, Eigen::MatrixXd::Ones(3, 1));
  EXPECT_THROW(d.rows({3}), ArgumentError);
  EXPECT_THROW(d.example_transformations(1), ArgumentError);
}

}  // namespace
}  // namespace posekit
