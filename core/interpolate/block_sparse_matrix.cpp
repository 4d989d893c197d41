#include "interpolate/block_sparse_matrix.hpp"

#include <algorithm>

namespace posekit::interpolation {

BlockSparseMatrix3::BlockSparseMatrix3(int block_count, const std::vector<std::pair<int, int>>& pairs)
    : column_start_(static_cast<size_t>(block_count) + 1, 0), slot_of_diagonal_(static_cast<size_t>(block_count)) {
  // Block rows per block column in one array (a whole mesh has tens of thousands of columns): the
  // diagonal and both blocks of every pair, then sorted and made unique column by column.
  std::vector<int> count(static_cast<size_t>(block_count), 1);
  for (const auto& [i, j] : pairs) {
    ++count[static_cast<size_t>(i)];
    ++count[static_cast<size_t>(j)];
  }
  std::vector<int> start(static_cast<size_t>(block_count) + 1, 0);
  for (int j = 0; j < block_count; ++j) {
    start[static_cast<size_t>(j) + 1] = start[static_cast<size_t>(j)] + count[static_cast<size_t>(j)];
  }
  std::vector<int> rows(static_cast<size_t>(start[static_cast<size_t>(block_count)]));
  std::vector<int> next(start.begin(), start.end() - 1);
  const auto put = [&](int row, int column) { rows[static_cast<size_t>(next[static_cast<size_t>(column)]++)] = row; };
  for (int i = 0; i < block_count; ++i) put(i, i);
  for (const auto& [i, j] : pairs) {
    put(i, j);
    put(j, i);
  }
  block_rows_.reserve(rows.size());
  for (int j = 0; j < block_count; ++j) {
    const auto begin = rows.begin() + start[static_cast<size_t>(j)];
    const auto end = rows.begin() + start[static_cast<size_t>(j) + 1];
    std::sort(begin, end);
    block_rows_.insert(block_rows_.end(), begin, std::unique(begin, end));
    column_start_[static_cast<size_t>(j) + 1] = static_cast<int>(block_rows_.size());
  }
  // Column-major storage written directly: each block column gives three scalar columns with the same
  // rows, three consecutive rows per block.
  const int size = 3 * block_count;
  matrix_.resize(size, size);
  matrix_.resizeNonZeros(static_cast<Eigen::Index>(block_rows_.size()) * 9);
  int* outer = matrix_.outerIndexPtr();
  int* inner = matrix_.innerIndexPtr();
  int position = 0;
  for (int j = 0; j < block_count; ++j) {
    for (int c = 0; c < 3; ++c) {
      outer[3 * j + c] = position;
      for (int k = column_start_[static_cast<size_t>(j)]; k < column_start_[static_cast<size_t>(j) + 1]; ++k) {
        for (int r = 0; r < 3; ++r) inner[position++] = 3 * block_rows_[static_cast<size_t>(k)] + r;
      }
    }
  }
  outer[size] = position;
  matrix_.coeffs().setZero();
  for (int i = 0; i < block_count; ++i) slot_of_diagonal_[static_cast<size_t>(i)] = slot(i, i);
}

BlockSparseMatrix3::Slot BlockSparseMatrix3::slot(int i, int j) const {
  const auto begin = block_rows_.begin() + column_start_[static_cast<size_t>(j)];
  const auto end = block_rows_.begin() + column_start_[static_cast<size_t>(j) + 1];
  const int index = static_cast<int>(std::lower_bound(begin, end, i) - begin);
  const int stride = 3 * static_cast<int>(end - begin);
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
