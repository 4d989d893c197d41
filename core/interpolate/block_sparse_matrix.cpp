#include "interpolate/block_sparse_matrix.hpp"

#include <algorithm>

namespace posekit::interpolation {

BlockSparseMatrix3::BlockSparseMatrix3(int block_count, const std::vector<std::pair<int, int>>& pairs)
    : column_blocks_(static_cast<size_t>(block_count)), slot_of_diagonal_(static_cast<size_t>(block_count)) {
  for (int i = 0; i < block_count; ++i) column_blocks_[static_cast<size_t>(i)].push_back(i);
  for (const auto& [i, j] : pairs) {
    column_blocks_[static_cast<size_t>(j)].push_back(i);
    column_blocks_[static_cast<size_t>(i)].push_back(j);
  }
  long long total = 0;
  for (std::vector<int>& rows : column_blocks_) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    total += static_cast<long long>(rows.size()) * 9;
  }
  // Column-major storage written directly: each block column gives three scalar columns with the same
  // rows, three consecutive rows per block.
  const int size = 3 * block_count;
  matrix_.resize(size, size);
  matrix_.resizeNonZeros(static_cast<Eigen::Index>(total));
  int* outer = matrix_.outerIndexPtr();
  int* inner = matrix_.innerIndexPtr();
  int position = 0;
  for (int j = 0; j < block_count; ++j) {
    const std::vector<int>& rows = column_blocks_[static_cast<size_t>(j)];
    for (int c = 0; c < 3; ++c) {
      outer[3 * j + c] = position;
      for (const int i : rows) {
        for (int r = 0; r < 3; ++r) inner[position++] = 3 * i + r;
      }
    }
  }
  outer[size] = position;
  matrix_.coeffs().setZero();
  for (int i = 0; i < block_count; ++i) slot_of_diagonal_[static_cast<size_t>(i)] = slot(i, i);
}

BlockSparseMatrix3::Slot BlockSparseMatrix3::slot(int i, int j) const {
  const std::vector<int>& rows = column_blocks_[static_cast<size_t>(j)];
  const auto found = std::lower_bound(rows.begin(), rows.end(), i);
  const int index = static_cast<int>(found - rows.begin());
  const int stride = 3 * static_cast<int>(rows.size());
  return Slot{matrix_.outerIndexPtr()[3 * j] + 3 * index, stride};
}

double BlockSparseMatrix3::mean_diagonal() const {
  if (slot_of_diagonal_.empty()) return 0.0;
  double sum = 0.0;
  const double* values = matrix_.valuePtr();
  for (const Slot& s : slot_of_diagonal_) {
    for (int c = 0; c < 3; ++c) sum += values[s.base + c * s.stride + c];
  }
  return sum / (3.0 * static_cast<double>(slot_of_diagonal_.size()));
}

}  // namespace posekit::interpolation
