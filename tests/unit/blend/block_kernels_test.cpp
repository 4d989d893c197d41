#include "blend/block_kernels.hpp"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <random>

namespace posekit::detail {
namespace {

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = value(random);
  return m;
}

// Row counts below, at and past the vector widths, and blocks taken from inside a wider matrix (an
// outer stride unlike the row count), as the iterations pass them.
TEST(BlockKernels, ProductOfMapsAndBlockMatchesEigen) {
  for (const Eigen::Index rows : {1, 3, 7, 8, 9, 33, 336}) {
    const Eigen::MatrixXd g = random_matrix(rows, 12, static_cast<unsigned>(rows));
    const Eigen::MatrixX3d t = random_matrix(rows, 3, 100 + static_cast<unsigned>(rows));
    for (int j = 0; j < 4; ++j) {
      const Eigen::Matrix3d expected = t.transpose() * g.middleCols<3>(3 * j);
      const Eigen::Matrix3d product = block_product(t, g.middleCols<3>(3 * j));
      EXPECT_LT((product - expected).cwiseAbs().maxCoeff(), 1e-12 * static_cast<double>(rows))
          << rows << " rows, block " << j;
    }
  }
}

TEST(BlockKernels, AccumulatedBlockMatchesEigen) {
  for (const Eigen::Index rows : {1, 5, 8, 17, 160}) {
    const Eigen::MatrixXd g = random_matrix(rows + 6, 9, static_cast<unsigned>(rows));
    const Eigen::Matrix3d m = random_matrix(3, 3, 7);
    Eigen::MatrixX3d side = random_matrix(rows + 6, 3, 8);
    Eigen::MatrixX3d expected = side;
    expected.middleRows(2, rows) += g.middleCols<3>(3).middleRows(2, rows) * m;
    accumulate_block(g.middleCols<3>(3).middleRows(2, rows), m, side.middleRows(2, rows));
    EXPECT_LT((side - expected).cwiseAbs().maxCoeff(), 1e-13) << rows << " rows";
    // The rows outside the block are untouched.
    EXPECT_EQ(side.topRows(2), expected.topRows(2));
    EXPECT_EQ(side.bottomRows(4), expected.bottomRows(4));
  }
}

TEST(BlockKernels, CholeskySolveMatchesEigen) {
  for (const Eigen::Index n : {1, 2, 9, 40, 161}) {
    const Eigen::MatrixXd a = random_matrix(n, n, static_cast<unsigned>(n));
    const Eigen::MatrixXd spd = a * a.transpose() + Eigen::MatrixXd::Identity(n, n);
    const Eigen::LLT<Eigen::MatrixXd> factor(spd);
    const Eigen::MatrixX3d b = random_matrix(n, 3, 3);
    Eigen::MatrixX3d x = b;
    cholesky_solve(factor.matrixLLT(), x);
    EXPECT_LT((spd * x - b).cwiseAbs().maxCoeff(), 1e-9) << n;
    EXPECT_LT((x - factor.solve(b)).cwiseAbs().maxCoeff(), 1e-9) << n;
  }
}

// The factored product of a block of rows inside taller factors, for row counts within a tile, at
// its width and across tiles.
TEST(BlockKernels, FactoredProductMatchesTheProductThenTheWeightedSum) {
  for (const Eigen::Index rows : {1, 15, 16, 17, 50}) {
    const Eigen::MatrixXd multiplied = random_matrix(rows + 5, 6, static_cast<unsigned>(rows));
    const Eigen::MatrixXd summed = random_matrix(rows + 5, 4, 50 + static_cast<unsigned>(rows));
    const Eigen::MatrixXd maps = random_matrix(6, 12, 9);
    const Eigen::MatrixXd mapped = multiplied.middleRows(3, rows) * maps;
    Eigen::MatrixX3d expected = Eigen::MatrixX3d::Zero(rows, 3);
    for (int j = 0; j < 4; ++j) {
      for (int c = 0; c < 3; ++c) expected.col(c) += summed.col(j).segment(3, rows).cwiseProduct(mapped.col(3 * j + c));
    }
    Eigen::MatrixX3d out = Eigen::MatrixX3d::Constant(rows + 2, 3, 7.0);
    factored_block_product(multiplied.middleRows(3, rows), summed.middleRows(3, rows), maps, out.middleRows(1, rows));
    EXPECT_LT((out.middleRows(1, rows) - expected).cwiseAbs().maxCoeff(), 1e-13) << rows << " rows";
    EXPECT_EQ(out(0, 0), 7.0);
    EXPECT_EQ(out(rows + 1, 2), 7.0);
  }
}

}  // namespace
}  // namespace posekit::detail
