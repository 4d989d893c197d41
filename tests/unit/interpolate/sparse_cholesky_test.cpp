// The Gauss-Newton factorization: both of its factorizations solve a positive definite system alike
// and report one that breaks down, and the size of the system picks between them.
#include "interpolate/sparse_cholesky.hpp"

#include <posekit/error.hpp>

#include <Eigen/CholmodSupport>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace posekit::testing {
namespace {

// The Laplacian of a side x side grid plus `shift` times the identity.
Eigen::SparseMatrix<double> shifted_grid_laplacian(int side, double shift) {
  std::vector<Eigen::Triplet<double>> entries;
  const auto index = [side](int i, int j) { return i * side + j; };
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      entries.emplace_back(index(i, j), index(i, j), shift);
      const int neighbours[2][2] = {{i + 1, j}, {i, j + 1}};
      for (const auto& n : neighbours) {
        if (n[0] >= side || n[1] >= side) continue;
        const int a = index(i, j);
        const int b = index(n[0], n[1]);
        entries.emplace_back(a, a, 1.0);
        entries.emplace_back(b, b, 1.0);
        entries.emplace_back(a, b, -1.0);
        entries.emplace_back(b, a, -1.0);
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(side * side, side * side);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

TEST(SparseCholesky, BothFactorizationsSolveThePositiveDefiniteSystem) {
  const Eigen::SparseMatrix<double> matrix = shifted_grid_laplacian(40, 1e-3);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(matrix.rows(), -1.0, 2.0);
  interpolation::SparseCholesky simplicial;
  interpolation::SparseCholesky cholmod(0);
  Eigen::VectorXd solutions[2];
  int k = 0;
  for (interpolation::SparseCholesky* solver : {&simplicial, &cholmod}) {
    solver->analyze_pattern(matrix);
    ASSERT_TRUE(solver->factorize(matrix));
    solutions[k] = solver->solve(rhs);
    EXPECT_LT((matrix * solutions[k] - rhs).norm(), 1e-9 * rhs.norm()) << "solver " << k;
    ++k;
  }
  EXPECT_FALSE(simplicial.uses_cholmod());
  EXPECT_TRUE(cholmod.uses_cholmod());
  EXPECT_LT((solutions[0] - solutions[1]).norm(), 1e-8 * solutions[0].norm());
}

// A side^3 grid's Laplacian plus a diagonal that varies with `seed`: a pattern whose factor is dense
// enough for CHOLMOD to factorize supernodally, with values that differ from seed to seed.
Eigen::SparseMatrix<double> varied_cube_laplacian(int side, double seed) {
  std::vector<Eigen::Triplet<double>> entries;
  const auto index = [side](int i, int j, int k) { return (i * side + j) * side + k; };
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      for (int k = 0; k < side; ++k) {
        const int a = index(i, j, k);
        entries.emplace_back(a, a, 0.1 + std::abs(std::sin(seed * (a + 1))));
        const int neighbours[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (const auto& n : neighbours) {
          if (n[0] >= side || n[1] >= side || n[2] >= side) continue;
          const int b = index(n[0], n[1], n[2]);
          const double weight = 1.0 + 0.5 * std::cos(seed * (a + 3 * b));
          entries.emplace_back(a, a, weight);
          entries.emplace_back(b, b, weight);
          entries.emplace_back(a, b, -weight);
          entries.emplace_back(b, a, -weight);
        }
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(side * side * side, side * side * side);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

TEST(SparseCholesky, RefactorizesSupernodallyToTheBitsOfCholmodsOwnCall) {
  // The supernodal path hands CHOLMOD the permuted matrix it keeps; CHOLMOD's own factorization
  // call (here through Eigen's wrapper) builds it afresh. Both must give the same solution, bit for
  // bit, for every refill of the values. Both read the lower triangle alone: the upper one is off.
  interpolation::SparseCholesky solver(0);
  solver.analyze_pattern(varied_cube_laplacian(14, 1.0));
  ASSERT_TRUE(solver.factorizes_supernodally());
  for (const double seed : {1.0, 2.5, 7.0}) {
    Eigen::SparseMatrix<double> matrix = varied_cube_laplacian(14, seed);
    for (int column = 0; column < matrix.outerSize(); ++column) {
      for (Eigen::SparseMatrix<double>::InnerIterator entry(matrix, column); entry; ++entry) {
        if (entry.row() < column) entry.valueRef() *= 1.001;
      }
    }
    const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(matrix.rows(), -1.0, 2.0 + seed);
    ASSERT_TRUE(solver.factorize(matrix)) << "seed " << seed;
    const Eigen::VectorXd ours = solver.solve(rhs);
    Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> reference(matrix);
    ASSERT_EQ(reference.info(), Eigen::Success);
    const Eigen::VectorXd expected = reference.solve(rhs);
    const Eigen::SparseMatrix<double> symmetric = matrix.selfadjointView<Eigen::Lower>();
    EXPECT_LT((symmetric * ours - rhs).norm(), 1e-9 * rhs.norm()) << "seed " << seed;
    EXPECT_EQ((ours - expected).cwiseAbs().maxCoeff(), 0.0) << "seed " << seed;
  }
}

TEST(SparseCholesky, TheSupernodalPathReportsAMatrixThatIsNotPositiveDefinite) {
  Eigen::SparseMatrix<double> matrix = varied_cube_laplacian(14, 1.0);
  interpolation::SparseCholesky solver(0);
  solver.analyze_pattern(matrix);
  ASSERT_TRUE(solver.factorizes_supernodally());
  ASSERT_TRUE(solver.factorize(matrix));
  matrix.coeffRef(1000, 1000) = -50.0;
  EXPECT_FALSE(solver.factorize(matrix));
}

TEST(SparseCholesky, CholmodRefusesAnUncompressedMatrixOrAnotherPattern) {
  Eigen::SparseMatrix<double> matrix = shifted_grid_laplacian(5, 1.0);
  interpolation::SparseCholesky solver(0);
  solver.analyze_pattern(matrix);
  EXPECT_THROW(solver.factorize(shifted_grid_laplacian(6, 1.0)), Error);
  matrix.uncompress();
  EXPECT_THROW(solver.analyze_pattern(matrix), Error);
}

TEST(SparseCholesky, BothReportASingularMatrix) {
  Eigen::SparseMatrix<double> matrix(100, 100);
  matrix.setIdentity();
  matrix.coeffRef(5, 5) = 0.0;
  for (const Eigen::Index cholmod_rows : {Eigen::Index{0}, interpolation::SparseCholesky::kCholmodRows}) {
    interpolation::SparseCholesky solver(cholmod_rows);
    solver.analyze_pattern(matrix);
    EXPECT_FALSE(solver.factorize(matrix)) << "CHOLMOD from " << cholmod_rows << " rows";
  }
}

TEST(SparseCholesky, CholmodReportsAMatrixThatIsNotPositiveDefinite) {
  const Eigen::SparseMatrix<double> matrix = shifted_grid_laplacian(10, -1.0);
  interpolation::SparseCholesky solver(0);
  solver.analyze_pattern(matrix);
  EXPECT_FALSE(solver.factorize(matrix));
}

TEST(SparseCholesky, LargeSystemsGoToCholmod) {
  const Eigen::Index rows = interpolation::SparseCholesky::kCholmodRows;
  Eigen::SparseMatrix<double> identity(rows, rows);
  identity.setIdentity();
  interpolation::SparseCholesky solver;
  solver.analyze_pattern(identity);
  EXPECT_TRUE(solver.uses_cholmod());
  ASSERT_TRUE(solver.factorize(identity));
  const Eigen::VectorXd rhs = Eigen::VectorXd::Constant(rows, 3.0);
  EXPECT_LT((solver.solve(rhs) - rhs).norm(), 1e-12);
}

}  // namespace
}  // namespace posekit::testing
