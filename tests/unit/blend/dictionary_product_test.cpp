#include "blend/dictionary_product.hpp"

#include <posekit/blend_dictionary.hpp>

#include <gtest/gtest.h>

#include <random>

namespace posekit::detail {
namespace {

// Three examples and weights of every kind a dictionary holds: a constant one, `dense` - 1 dense ones
// (eigenfunctions), three nonzero on a tenth of the vertices (bones) and one that is zero everywhere.
// With more dense weights than the 10 coordinates of [X 1], the product takes the other order.
BlendDictionary mixed_dictionary(int vertices, bool every_atom, int dense = 3) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::MatrixX3d> examples;
  for (int k = 0; k < 3; ++k) {
    Eigen::MatrixX3d x(vertices, 3);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = value(random);
    examples.push_back(x);
  }
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(vertices, dense + 4);
  weights.col(0).setConstant(0.5);
  for (int v = 0; v < vertices; ++v) {
    for (int j = 1; j < dense; ++j) weights(v, j) = value(random);
    for (int j = 0; j < 3; ++j) {
      if (v >= (j + 3) * vertices / 10 && v < (j + 4) * vertices / 10) weights(v, dense + j) = value(random);
    }
  }
  if (every_atom) return BlendDictionary(examples, weights);
  std::vector<DictionaryAtom> atoms;  // every other atom, in an order unlike the full dictionary's
  for (int j = static_cast<int>(weights.cols()) - 1; j >= 0; --j) {
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a < 4; ++a) {
        if ((j + k + a) % 2 == 0) atoms.push_back({k, j, a});
      }
    }
  }
  return BlendDictionary(examples, weights, atoms);
}

void expect_dense_product(const BlendDictionary& dictionary, int sparse_atoms) {
  const DictionaryProduct product(dictionary);
  EXPECT_EQ(product.rows(), dictionary.vertex_count());
  EXPECT_EQ(product.cols(), dictionary.atom_count());
  EXPECT_EQ(product.sparse_atom_count(), sparse_atoms);
  const Eigen::MatrixX3d t = Eigen::MatrixX3d::Random(dictionary.atom_count(), 3);
  const Eigen::MatrixX3d expected = dictionary.matrix() * t;
  EXPECT_LE((product(t) - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
}

TEST(DictionaryProduct, EqualsTheDictionaryMatrixTimesTheTransformations) {
  // 1000 vertices: not a multiple of the block of vertices. The four bone-like weights (three
  // banded, one zero) have 4 * 3 atoms each.
  expect_dense_product(mixed_dictionary(1000, true), 4 * 12);
}

TEST(DictionaryProduct, FollowsTheAtomsOfAReducedDictionary) {
  const BlendDictionary reduced = mixed_dictionary(1000, false);
  int sparse = 0;
  for (const DictionaryAtom& a : reduced.atoms()) sparse += a.weight >= 3 ? 1 : 0;
  expect_dense_product(reduced, sparse);
}

TEST(DictionaryProduct, EqualsTheDictionaryMatrixWithMoreWeightsThanCoordinates) {
  expect_dense_product(mixed_dictionary(1000, true, 14), 4 * 12);
  const BlendDictionary reduced = mixed_dictionary(1000, false, 14);
  int sparse = 0;
  for (const DictionaryAtom& a : reduced.atoms()) sparse += a.weight >= 14 ? 1 : 0;
  expect_dense_product(reduced, sparse);
}

}  // namespace
}  // namespace posekit::detail
