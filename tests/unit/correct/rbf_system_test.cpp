// The RBF saddle-point system and its factorization: the bordered block LDL^T against a direct
// factorization, blocked against full refactorization, interpolation of the centers, exact
// reproduction of quadratic polynomials, and singular systems reported as errors.
#include "correct/rbf_system.hpp"

#include <posekit/cpu_device.hpp>
#include <posekit/error.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace posekit {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

Points4 random_points(std::mt19937_64& engine, Index count) {
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::uniform_real_distribution<double> time(0.0, 1.0);
  Points4 points(count, 4);
  for (Index i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) points(i, k) = coordinate(engine);
    points(i, 3) = time(engine);
  }
  return points;
}

// A smooth, non-polynomial vector field on R^4.
Eigen::MatrixX3d smooth_values(const Points4& points) {
  Eigen::MatrixX3d values(points.rows(), 3);
  for (Index i = 0; i < points.rows(); ++i) {
    const double x = points(i, 0), y = points(i, 1), z = points(i, 2), t = points(i, 3);
    values(i, 0) = std::sin(2.0 * x + t) * std::cos(y);
    values(i, 1) = std::exp(-0.5 * (x * x + z * z)) + 0.3 * t * y;
    values(i, 2) = std::cos(1.5 * z - t) + 0.2 * x * y;
  }
  return values;
}

double relative_difference(const MatrixXd& actual, const MatrixXd& expected) {
  return (actual - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
}

// Feeds `points` to `system` in batches of the given sizes.
void add_in_batches(detail::RbfSystem& system, const Points4& points,
                    const std::vector<Index>& batches) {
  Index first = 0;
  for (const Index size : batches) {
    system.add_centers(points.middleRows(first, size));
    first += size;
  }
  ASSERT_EQ(first, points.rows());
}

// A random symmetric indefinite matrix whose small diagonal forces row exchanges inside the blocks
// of D.
MatrixXd random_symmetric(Index size, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal;
  MatrixXd matrix(size, size);
  for (Index i = 0; i < matrix.size(); ++i) matrix.data()[i] = normal(engine);
  matrix = (matrix + matrix.transpose()).eval();
  matrix.diagonal() *= 1e-3;
  return matrix;
}

// Bordering in uneven steps gives the block LDL^T of the whole matrix with those blocks: L unit
// lower block triangular, D block diagonal, L D L^T = A, and each block of D the Schur complement
// of the rows before it (computed here with a dense solver); solves match a dense solver.
TEST(BorderedBlockLdlt, BorderingInStepsFactorizesTheWholeMatrix) {
  const std::vector<Index> blocks = {7, 5, 13, 1, 30};
  const Index size = 7 + 5 + 13 + 1 + 30;
  const MatrixXd matrix = random_symmetric(size, 11);

  detail::BorderedBlockLdlt ldlt(size);
  Index n = 0;
  for (const Index m : blocks) {
    const double pivot = ldlt.append(matrix.block(n, 0, m, n), matrix.block(n, n, m, m));
    EXPECT_GT(pivot, 0.0);
    n += m;
    ASSERT_EQ(ldlt.size(), n);

    const MatrixXd lower = ldlt.unit_lower();
    const MatrixXd diagonal = ldlt.block_diagonal();
    const MatrixXd leading = matrix.topLeftCorner(n, n);
    EXPECT_LT(relative_difference(lower * diagonal * lower.transpose(), leading), 1e-12)
        << "after " << n << " rows";
    Index start = 0;
    for (std::size_t k = 0; start < n; start += blocks[k], ++k) {
      const Index rows = blocks[k];
      EXPECT_TRUE((lower.block(start, start, rows, n - start) ==
                   MatrixXd::Identity(rows, n - start)))
          << "L is not unit lower block triangular at block " << k;
      EXPECT_TRUE(diagonal.block(start, start + rows, rows, n - start - rows).isZero(0.0))
          << "D is not block diagonal at block " << k;
      const MatrixXd before = matrix.topLeftCorner(start, start);
      const MatrixXd coupling = matrix.block(0, start, start, rows);
      MatrixXd schur = matrix.block(start, start, rows, rows);
      if (start > 0) schur -= coupling.transpose() * before.partialPivLu().solve(coupling);
      EXPECT_LT(relative_difference(diagonal.block(start, start, rows, rows), schur), 1e-10)
          << "block " << k << " of D after " << n << " rows";
    }

    const MatrixXd rhs = MatrixXd::Random(n, 3);
    const MatrixXd expected = leading.partialPivLu().solve(rhs);
    EXPECT_LT(relative_difference(ldlt.solve(rhs), expected), 1e-10) << "after " << n << " rows";
  }
  EXPECT_EQ(ldlt.block_count(), static_cast<Index>(blocks.size()));
}

// A first block with a zero corner, like the polynomial rows of the RBF system, needs the pivoting
// inside the block.
TEST(BorderedBlockLdlt, FactorizesASaddlePointFirstBlock) {
  MatrixXd matrix = random_symmetric(40, 13);
  matrix.block(20, 20, 5, 5).setZero();
  detail::BorderedBlockLdlt ldlt;
  EXPECT_GT(ldlt.append(MatrixXd(25, 0), matrix.topLeftCorner(25, 25)), 1e-8);
  EXPECT_GT(ldlt.append(matrix.block(25, 0, 15, 25), matrix.block(25, 25, 15, 15)), 1e-8);
  const MatrixXd rhs = MatrixXd::Random(40, 2);
  EXPECT_LT(relative_difference(ldlt.solve(rhs), matrix.partialPivLu().solve(rhs)), 1e-10);
}

TEST(BorderedBlockLdlt, ReportsAZeroPivotForARepeatedRowAndColumn) {
  MatrixXd matrix = random_symmetric(12, 14);
  matrix.row(10) = matrix.row(3);
  matrix.col(10) = matrix.col(3);
  detail::BorderedBlockLdlt ldlt;
  ASSERT_GT(ldlt.append(MatrixXd(8, 0), matrix.topLeftCorner(8, 8)), 0.0);
  const double pivot = ldlt.append(matrix.block(8, 0, 4, 8), matrix.block(8, 8, 4, 4));
  EXPECT_LT(pivot, 1e-14);
}

TEST(BorderedBlockLdlt, RejectsBlocksThatDoNotBorderTheMatrix) {
  detail::BorderedBlockLdlt ldlt;
  ldlt.append(MatrixXd(3, 0), MatrixXd::Identity(3, 3));
  EXPECT_THROW(ldlt.append(MatrixXd(2, 2), MatrixXd::Identity(2, 2)), ArgumentError);
  EXPECT_THROW(ldlt.append(MatrixXd(2, 3), MatrixXd::Identity(3, 3)), ArgumentError);
  EXPECT_THROW(ldlt.solve(MatrixXd(4, 1)), ArgumentError);
}

class RbfSystemTest : public ::testing::Test {
 protected:
  std::unique_ptr<Device> device = make_cpu_device();
};

// Random centers in batches of a fitting run: the blocked factorization gives the full
// factorization's coefficients. Both are backward stable, so they differ by about
// cond(A) * epsilon relative to the coefficients: near 1e-12 here; 1e-8 leaves room for rounding
// that differs with the instruction set.
TEST_F(RbfSystemTest, BlockedUpdateGivesTheFullFactorizationsCoefficients) {
  std::mt19937_64 engine(5);
  const Points4 points = random_points(engine, 352);
  const Eigen::MatrixX3d values = smooth_values(points);
  const std::vector<Index> batches = {64, 32, 128, 1, 127};

  detail::RbfSystem blocked(*device, true, points.rows());
  detail::RbfSystem full(*device, false);
  Index count = 0;
  for (const Index size : batches) {
    blocked.add_centers(points.middleRows(count, size));
    full.add_centers(points.middleRows(count, size));
    count += size;
    const RbfField from_blocked = blocked.solve(values.topRows(count));
    const RbfField from_full = full.solve(values.topRows(count));
    ASSERT_EQ(from_blocked.centers, points.topRows(count));
    ASSERT_EQ(from_full.centers, points.topRows(count));
    EXPECT_LT(relative_difference(from_blocked.weights, from_full.weights), 1e-8)
        << count << " centers";
    EXPECT_LT(relative_difference(from_blocked.polynomial, from_full.polynomial), 1e-8)
        << count << " centers";
  }
}

TEST_F(RbfSystemTest, FieldInterpolatesItsCenters) {
  std::mt19937_64 engine(6);
  const Points4 points = random_points(engine, 300);
  const Eigen::MatrixX3d values = smooth_values(points);
  for (const bool blocked : {true, false}) {
    detail::RbfSystem system(*device, blocked);
    add_in_batches(system, points, {100, 100, 100});
    const RbfField field = system.solve(values);
    const std::unique_ptr<DeviceField> uploaded = device->upload_field(field);
    Eigen::MatrixX3d at_centers(points.rows(), 3);
    device->evaluate_rbf(*uploaded, points, at_centers);
    EXPECT_LT(relative_difference(at_centers, values), 1e-10) << (blocked ? "blocked" : "full");
  }
}

TEST_F(RbfSystemTest, ReproducesAQuadraticPolynomialWithZeroWeights) {
  std::mt19937_64 engine(7);
  const Points4 points = random_points(engine, 200);
  RbfPolynomial polynomial;
  std::uniform_real_distribution<double> coefficient(-2.0, 2.0);
  for (Index i = 0; i < polynomial.size(); ++i) polynomial.data()[i] = coefficient(engine);
  Eigen::MatrixX3d values(points.rows(), 3);
  for (Index i = 0; i < points.rows(); ++i) {
    const double x = points(i, 0), y = points(i, 1), z = points(i, 2), t = points(i, 3);
    Eigen::Matrix<double, 1, 15> basis;
    basis << 1, x, y, z, t, x * x, x * y, x * z, x * t, y * y, y * z, y * t, z * z, z * t, t * t;
    values.row(i) = basis * polynomial;
  }
  for (const bool blocked : {true, false}) {
    detail::RbfSystem system(*device, blocked);
    add_in_batches(system, points, {40, 80, 80});
    const RbfField field = system.solve(values);
    EXPECT_LT(field.weights.cwiseAbs().maxCoeff(), 1e-9 * values.cwiseAbs().maxCoeff())
        << (blocked ? "blocked" : "full");
    EXPECT_LT(relative_difference(field.polynomial, polynomial), 1e-9)
        << (blocked ? "blocked" : "full");
  }
}

TEST_F(RbfSystemTest, RepeatedCenterIsASingularSystem) {
  std::mt19937_64 engine(8);
  Points4 points = random_points(engine, 60);
  points.row(50) = points.row(7);
  for (const bool blocked : {true, false}) {
    detail::RbfSystem system(*device, blocked);
    system.add_centers(points.topRows(40));
    try {
      system.add_centers(points.bottomRows(20));
      ADD_FAILURE() << "a repeated center was accepted (" << (blocked ? "blocked" : "full") << ")";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("singular"), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("centers 41 to 60"), std::string::npos)
          << error.what();
    }
  }
}

TEST_F(RbfSystemTest, CentersAtOneTimeCannotDetermineThePolynomial) {
  std::mt19937_64 engine(9);
  Points4 points = random_points(engine, 50);
  points.col(3).setConstant(0.25);
  for (const bool blocked : {true, false}) {
    detail::RbfSystem system(*device, blocked);
    EXPECT_THROW(system.add_centers(points), Error) << (blocked ? "blocked" : "full");
  }
}

TEST_F(RbfSystemTest, FewerThanFifteenCentersCannotDetermineThePolynomial) {
  std::mt19937_64 engine(10);
  const Points4 points = random_points(engine, 14);
  for (const bool blocked : {true, false}) {
    detail::RbfSystem system(*device, blocked);
    try {
      system.add_centers(points);
      ADD_FAILURE() << "14 centers were accepted (" << (blocked ? "blocked" : "full") << ")";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("the first 14 centers"), std::string::npos)
          << error.what();
    }
  }
}

TEST_F(RbfSystemTest, RejectsEmptyOrNonFiniteBatchesAndMismatchedValues) {
  detail::RbfSystem system(*device, true);
  EXPECT_THROW(system.add_centers(Points4(0, 4)), ArgumentError);
  Points4 points = Points4::Zero(20, 4);
  points(3, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(system.add_centers(points), ArgumentError);

  std::mt19937_64 engine(12);
  system.add_centers(random_points(engine, 30));
  EXPECT_THROW(system.solve(Eigen::MatrixX3d::Zero(29, 3)), ArgumentError);
}

}  // namespace
}  // namespace posekit
