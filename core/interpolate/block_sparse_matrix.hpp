// A sparse matrix made of 3 x 3 blocks whose pattern is fixed once and whose values are refilled
// many times: Gauss-Newton and frame systems change their values for every interpolation weight but
// never their structure, so the symbolic factorization is done once.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <utility>
#include <vector>

namespace posekit::interpolation {

class BlockSparseMatrix3 {
 public:
  /// Where block (i, j) lives: entry (3i + r, 3j + c) is values[base + c * stride + r].
  struct Slot {
    int base = -1;
    int stride = 0;
  };

  BlockSparseMatrix3() = default;
  /// A 3n x 3n matrix with a block at every (i, j) and (j, i) of `pairs` and on the diagonal.
  BlockSparseMatrix3(int block_count, const std::vector<std::pair<int, int>>& pairs);

  /// The slot of block (i, j); the block must be in the pattern.
  Slot slot(int i, int j) const;
  Slot diagonal_slot(int i) const { return slot_of_diagonal_[static_cast<size_t>(i)]; }
  void set_zero() { matrix_.coeffs().setZero(); }
  void add(Slot slot, const Eigen::Matrix3d& block) {
    double* values = matrix_.valuePtr();
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) values[slot.base + c * slot.stride + r] += block(r, c);
    }
  }
  void add_diagonal(int i, double value) {
    const Slot s = slot_of_diagonal_[static_cast<size_t>(i)];
    double* values = matrix_.valuePtr();
    for (int c = 0; c < 3; ++c) values[s.base + c * s.stride + c] += value;
  }
  /// Mean of the diagonal entries.
  double mean_diagonal() const;
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }
  int block_count() const { return static_cast<int>(slot_of_diagonal_.size()); }

 private:
  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> column_start_;  // per block column: where its block rows start in block_rows_
  std::vector<int> block_rows_;    // per block column: block rows, ascending
  std::vector<Slot> slot_of_diagonal_;
};

}  // namespace posekit::interpolation
