#include "correct/rbf_system.hpp"

#include <posekit/error.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace posekit::detail {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

// A pivot below size * epsilon * (largest entry) is indistinguishable from zero at this size: the
// usual rank-revealing threshold of an LU factorization. The systems of well-spread centers reach
// condition numbers of 1e6 to 1e9, far above it.
double singular_pivot_threshold(Index size) {
  return static_cast<double>(size) * std::numeric_limits<double>::epsilon();
}

double largest_magnitude(const Eigen::Ref<const MatrixXd>& matrix) {
  return matrix.size() == 0 ? 0.0 : matrix.cwiseAbs().maxCoeff();
}

// Splits [0, count) into one contiguous piece per worker (at least `grain` wide) and runs
// work(begin, width) on each. Eigen's own kernels are single-threaded here, so the triangular solve
// and the products of the update are shared out by right-hand sides; a few wide pieces keep each
// piece efficient.
template <typename Work>
void for_each_piece(Index count, Index grain, const Work& work) {
  if (count <= 0) return;
  const Index workers = std::max(1, tbb::this_task_arena::max_concurrency());
  const Index pieces = std::clamp<Index>(count / std::max<Index>(grain, 1), 1, workers);
  const Index width = (count + pieces - 1) / pieces;
  tbb::parallel_for(tbb::blocked_range<Index>(0, pieces, 1),
                    [&](const tbb::blocked_range<Index>& range) {
                      for (Index piece = range.begin(); piece < range.end(); ++piece) {
                        const Index begin = piece * width;
                        const Index end = std::min(count, begin + width);
                        if (begin < end) work(begin, end - begin);
                      }
                    });
}

constexpr Index kRightHandSidesPerPiece = 16;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format_ratio(double ratio) {
  std::ostringstream text;
  text.precision(2);
  text << ratio;
  return text.str();
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// BorderedBlockLdlt
//
// Bordering A = L D L^T with [[A, B], [B^T, C]] (B = bottom^T):
//   [[A, B], [B^T, C]] = [[L, 0], [X, I]] [[D, 0], [0, S]] [[L^T, X^T], [0, I]]
// gives L D X^T = B, so with T = L^-1 B and W = D^-1 T the new rows of L are X = W^T, and the new
// block of D is the Schur complement S = C - X D X^T = C - T^T W, symmetric like C. Only T needs a
// triangular solve with the whole of L (n^2 m flops); W costs a solve with each m by m block of D.
// A bordered LU needs two such solves (L^-1 P B and B^T U^-1), twice the work, for the same
// Schur complement and hence the same pivots.

BorderedBlockLdlt::BorderedBlockLdlt(Index max_size) : max_size_(std::max<Index>(max_size, 0)) {}

void BorderedBlockLdlt::reserve(Index size) {
  const Index capacity = factors_.rows();
  if (size <= capacity) return;
  // Geometric growth: copying the factors every round would cost O(N^2) per round. Only the block
  // rows [L_k, D_k] are copied: the part above the diagonal blocks is never used (nor touched, so
  // its memory is never committed).
  Index grown = std::max(size, capacity + capacity / 2);
  if (max_size_ > 0) grown = std::max(size, std::min(grown, max_size_));
  MatrixXd larger(grown, grown);
  for (std::size_t k = 0; k < block_starts_.size(); ++k) {
    const Index start = block_starts_[k];
    larger.block(start, 0, block_size(k), start + block_size(k)) =
        factors_.block(start, 0, block_size(k), start + block_size(k));
  }
  factors_.swap(larger);
}

Index BorderedBlockLdlt::block_size(std::size_t block) const {
  const Index end = block + 1 < block_starts_.size() ? block_starts_[block + 1] : size_;
  return end - block_starts_[block];
}

void BorderedBlockLdlt::solve_diagonal_block(std::size_t block,
                                             Eigen::Ref<MatrixXd> block_rows) const {
  // D_k^-1 = U_k^-1 L_k^-1 P_k.
  const Index start = block_starts_[block];
  const Index size = block_rows.rows();
  const MatrixXd original = block_rows;
  for (Index j = 0; j < size; ++j) {
    block_rows.row(j) = original.row(row_order_[static_cast<std::size_t>(start + j)] - start);
  }
  const auto lu = factors_.block(start, start, size, size);
  lu.triangularView<Eigen::UnitLower>().solveInPlace(block_rows);
  lu.triangularView<Eigen::Upper>().solveInPlace(block_rows);
}

double BorderedBlockLdlt::append(const Eigen::Ref<const MatrixXd>& bottom,
                                 const Eigen::Ref<const MatrixXd>& corner) {
  const Index n = size_;
  const Index m = corner.rows();
  if (corner.cols() != m || bottom.rows() != m || bottom.cols() != n) {
    throw ArgumentError("BorderedBlockLdlt::append: blocks of " + std::to_string(bottom.rows()) +
                        "x" + std::to_string(bottom.cols()) + " and " +
                        std::to_string(corner.rows()) + "x" + std::to_string(corner.cols()) +
                        " do not border a " + std::to_string(n) + "x" + std::to_string(n) +
                        " matrix");
  }
  if (m == 0) return 1.0;
  reserve(n + m);

  auto schur = factors_.block(n, n, m, m);
  schur.triangularView<Eigen::Lower>() = corner;
  schur.triangularView<Eigen::StrictlyUpper>().setZero();
  largest_entry_ = std::max({largest_entry_, largest_magnitude(bottom), largest_magnitude(schur)});

  const std::size_t blocks = block_starts_.size();
  if (n > 0) {
    // T and W live outside factors_, so that its part above the diagonal blocks stays untouched
    // and its memory uncommitted.
    MatrixXd t = bottom.transpose();  // T = L^-1 B
    MatrixXd w(n, m);                 // W = D^-1 T
    for_each_piece(m, kRightHandSidesPerPiece, [&](Index first, Index count) {
      auto t_piece = t.middleCols(first, count);
      // Block forward substitution: the diagonal blocks of L are identities, so each block row is
      // one product with the rows of T already solved.
      for (std::size_t k = 1; k < blocks; ++k) {
        const Index start = block_starts_[k];
        t_piece.middleRows(start, block_size(k)).noalias() -=
            factors_.block(start, 0, block_size(k), start) * t_piece.topRows(start);
      }
      auto w_piece = w.middleCols(first, count);
      w_piece = t_piece;
      for (std::size_t k = 0; k < blocks; ++k) {
        solve_diagonal_block(k, w_piece.middleRows(block_starts_[k], block_size(k)));
      }
    });
    // S = C - T^T W is symmetric: each piece of columns updates the lower triangle only, from its
    // diagonal down, and the LU below reads the upper triangle as its mirror.
    for_each_piece(m, kRightHandSidesPerPiece, [&](Index first, Index count) {
      schur.block(first, first, m - first, count).noalias() -=
          t.middleCols(first, m - first).transpose() * w.middleCols(first, count);
    });
    factors_.block(n, 0, m, n) = w.transpose();  // the new rows of L
  }

  const Eigen::PartialPivLU<MatrixXd> block_lu{MatrixXd(schur.selfadjointView<Eigen::Lower>())};
  schur = block_lu.matrixLU();
  // P as a row order: row j of P X is row new_order(j) of X.
  const Eigen::VectorXi new_order =
      block_lu.permutationP() * Eigen::VectorXi::LinSpaced(m, 0, static_cast<int>(m - 1));
  row_order_.reserve(static_cast<std::size_t>(n + m));
  for (Index j = 0; j < m; ++j) row_order_.push_back(n + new_order(j));
  block_starts_.push_back(n);
  size_ = n + m;

  const double smallest_pivot = schur.diagonal().cwiseAbs().minCoeff();
  if (!(smallest_pivot > 0.0) || !(largest_entry_ > 0.0)) return 0.0;
  return smallest_pivot / largest_entry_;
}

MatrixXd BorderedBlockLdlt::solve(const Eigen::Ref<const MatrixXd>& rhs) const {
  if (rhs.rows() != size_) {
    throw ArgumentError("BorderedBlockLdlt::solve: right-hand side has " +
                        std::to_string(rhs.rows()) + " rows but the matrix is " +
                        std::to_string(size_) + "x" + std::to_string(size_));
  }
  MatrixXd x = rhs;
  const std::size_t blocks = block_starts_.size();
  for (std::size_t k = 1; k < blocks; ++k) {  // L^-1
    const Index start = block_starts_[k];
    x.middleRows(start, block_size(k)).noalias() -=
        factors_.block(start, 0, block_size(k), start) * x.topRows(start);
  }
  for (std::size_t k = 0; k < blocks; ++k) {  // D^-1
    solve_diagonal_block(k, x.middleRows(block_starts_[k], block_size(k)));
  }
  for (std::size_t k = blocks; k-- > 1;) {  // L^-T, from the last block up
    const Index start = block_starts_[k];
    x.topRows(start).noalias() -=
        factors_.block(start, 0, block_size(k), start).transpose() *
        x.middleRows(start, block_size(k));
  }
  return x;
}

MatrixXd BorderedBlockLdlt::unit_lower() const {
  MatrixXd lower = MatrixXd::Identity(size_, size_);
  for (std::size_t k = 1; k < block_starts_.size(); ++k) {
    const Index start = block_starts_[k];
    lower.block(start, 0, block_size(k), start) = factors_.block(start, 0, block_size(k), start);
  }
  return lower;
}

MatrixXd BorderedBlockLdlt::block_diagonal() const {
  MatrixXd diagonal = MatrixXd::Zero(size_, size_);
  for (std::size_t k = 0; k < block_starts_.size(); ++k) {
    const Index start = block_starts_[k];
    const Index size = block_size(k);
    const auto lu = factors_.block(start, start, size, size);
    const MatrixXd permuted = MatrixXd(lu.triangularView<Eigen::UnitLower>()) *
                              MatrixXd(lu.triangularView<Eigen::Upper>());
    auto block = diagonal.block(start, start, size, size);
    for (Index j = 0; j < size; ++j) {
      block.row(row_order_[static_cast<std::size_t>(start + j)] - start) = permuted.row(j);
    }
  }
  return diagonal;
}

// ---------------------------------------------------------------------------------------------
// RbfSystem

RbfSystem::RbfSystem(Device& device, bool blocked_update, Index max_centers)
    : device_(&device),
      blocked_(blocked_update),
      max_centers_(std::max<Index>(max_centers, 0)),
      centers_(0, 4),
      bordered_(max_centers_ > 0 ? max_centers_ + kRbfPolynomialTerms : 0) {}

RbfSystemTimes RbfSystem::add_centers(const Points4& new_centers) {
  const Index added = new_centers.rows();
  if (added == 0) throw ArgumentError("RbfSystem::add_centers: the batch of new centers is empty");
  if (!new_centers.allFinite()) {
    throw ArgumentError("RbfSystem::add_centers: a new center has a non-finite coordinate");
  }
  const Index old_count = centers_.rows();
  Points4 all(old_count + added, 4);
  all.topRows(old_count) = centers_;
  all.bottomRows(added) = new_centers;

  RbfSystemTimes times;
  auto start = std::chrono::steady_clock::now();
  // Blocked: only the new centers' rows (their columns follow by symmetry); full: every row.
  const Points4& rows = blocked_ ? new_centers : all;
  MatrixXd block(rows.rows(), all.rows() + kRbfPolynomialTerms);
  device_->assemble_rbf_block(rows, all, true, block);
  times.assembly = seconds_since(start);

  start = std::chrono::steady_clock::now();
  const double pivot = blocked_ ? extend_blocked(block, old_count) : refactorize_full(block);
  times.factorization = seconds_since(start);
  centers_ = std::move(all);

  const Index unknowns = centers_.rows() + kRbfPolynomialTerms;
  if (!(pivot > singular_pivot_threshold(unknowns))) {
    const std::string which =
        old_count == 0 ? "the first " + std::to_string(added) + " centers"
                       : "centers " + std::to_string(old_count + 1) + " to " +
                             std::to_string(old_count + added);
    throw Error("the RBF system is singular with " + which + " (smallest pivot " +
                format_ratio(pivot) +
                " of the largest entry): centers repeat, are fewer than 15, or lie on a quadric "
                "of R^4 (e.g. all at one time)");
  }
  return times;
}

double RbfSystem::extend_blocked(const MatrixXd& block, Index old_count) {
  const Index added = block.rows();
  const Index new_count = old_count + added;
  const auto polynomial = block.rightCols(kRbfPolynomialTerms);
  if (old_count == 0) {
    first_batch_ = added;
    const Index size = added + kRbfPolynomialTerms;
    MatrixXd corner(size, size);
    corner.topLeftCorner(added, added) = block.leftCols(added);
    corner.topRightCorner(added, kRbfPolynomialTerms) = polynomial;
    corner.bottomLeftCorner(kRbfPolynomialTerms, added) = polynomial.transpose();
    corner.bottomRightCorner(kRbfPolynomialTerms, kRbfPolynomialTerms).setZero();
    return bordered_.append(MatrixXd(size, 0), corner);
  }
  // The new rows in the unknowns' order [first batch, polynomial, later batches].
  const Index size = old_count + kRbfPolynomialTerms;
  MatrixXd bottom(added, size);
  bottom.leftCols(first_batch_) = block.leftCols(first_batch_);
  bottom.middleCols(first_batch_, kRbfPolynomialTerms) = polynomial;
  bottom.rightCols(old_count - first_batch_) =
      block.middleCols(first_batch_, old_count - first_batch_);
  return bordered_.append(bottom, block.middleCols(old_count, new_count - old_count));
}

double RbfSystem::refactorize_full(const MatrixXd& block) {
  const Index count = block.rows();
  const Index size = count + kRbfPolynomialTerms;
  MatrixXd system(size, size);
  system.topRows(count) = block;
  system.bottomLeftCorner(kRbfPolynomialTerms, count) = block.rightCols(kRbfPolynomialTerms).transpose();
  system.bottomRightCorner(kRbfPolynomialTerms, kRbfPolynomialTerms).setZero();
  const double largest = largest_magnitude(system);
  full_.compute(system);
  const double smallest_pivot = full_.matrixLU().diagonal().cwiseAbs().minCoeff();
  if (!(smallest_pivot > 0.0) || !(largest > 0.0)) return 0.0;
  return smallest_pivot / largest;
}

RbfField RbfSystem::solve(const Eigen::Ref<const Eigen::MatrixX3d>& center_values) const {
  const Index count = centers_.rows();
  if (center_values.rows() != count) {
    throw ArgumentError("RbfSystem::solve: " + std::to_string(center_values.rows()) +
                        " values for " + std::to_string(count) + " centers");
  }
  RbfField field;
  field.centers = centers_;
  if (count == 0) {
    field.weights.resize(0, 3);
    return field;
  }
  const Index size = count + kRbfPolynomialTerms;
  if (blocked_) {
    MatrixXd rhs = MatrixXd::Zero(size, 3);
    rhs.topRows(first_batch_) = center_values.topRows(first_batch_);
    rhs.bottomRows(count - first_batch_) = center_values.bottomRows(count - first_batch_);
    const MatrixXd x = bordered_.solve(rhs);
    field.weights.resize(count, 3);
    field.weights.topRows(first_batch_) = x.topRows(first_batch_);
    field.weights.bottomRows(count - first_batch_) = x.bottomRows(count - first_batch_);
    field.polynomial = x.middleRows(first_batch_, kRbfPolynomialTerms);
  } else {
    MatrixXd rhs = MatrixXd::Zero(size, 3);
    rhs.topRows(count) = center_values;
    const MatrixXd x = full_.solve(rhs);
    field.weights = x.topRows(count);
    field.polynomial = x.bottomRows(kRbfPolynomialTerms);
  }
  if (!field.weights.allFinite() || !field.polynomial.allFinite()) {
    throw Error("the RBF system's solution is not finite: the system is numerically singular");
  }
  return field;
}

}  // namespace posekit::detail
