#include "blend/dictionary_product.hpp"

#include "blend/block_kernels.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace posekit::detail {

DictionaryProduct::DictionaryProduct(const BlendDictionary& dictionary) : atom_count_(dictionary.atom_count()) {
  const int n = dictionary.vertex_count();
  const int k_count = dictionary.example_count();
  const Eigen::MatrixXd& weights = dictionary.weights();
  std::vector<int> slot(static_cast<size_t>(weights.cols()), -1);
  std::vector<int> dense;
  for (int j = 0; j < weights.cols(); ++j) {
    // A sparse entry costs a value, an index and the access through it: below a quarter of the
    // vertices the sparse columns cost less than the factored product.
    const Eigen::Index nonzeros = (weights.col(j).array() != 0.0).count();
    if (4 * nonzeros >= n) {
      slot[static_cast<size_t>(j)] = static_cast<int>(dense.size());
      dense.push_back(j);
    }
  }
  // D T = sum_r x_r .* (W M)_r = sum_j w_j .* ([X 1] M_j): a product of one factor with the maps,
  // summed against the other. The product costs the same either way; the sums run over the summed
  // factor's columns, so the narrower factor is summed.
  by_weight_ = 3 * k_count + 1 <= static_cast<int>(dense.size());
  coordinates_.resize(n, 3 * k_count + 1);
  for (int k = 0; k < k_count; ++k) coordinates_.middleCols<3>(3 * k) = dictionary.examples()[static_cast<size_t>(k)];
  coordinates_.col(3 * k_count).setOnes();
  dense_weights_.resize(n, static_cast<Eigen::Index>(dense.size()));
  for (size_t q = 0; q < dense.size(); ++q) dense_weights_.col(static_cast<Eigen::Index>(q)) = weights.col(dense[q]);

  std::vector<Eigen::Triplet<double>> entries;
  for (int p = 0; p < atom_count_; ++p) {
    const DictionaryAtom& a = dictionary.atoms()[static_cast<size_t>(p)];
    const int s = slot[static_cast<size_t>(a.weight)];
    if (s >= 0) {
      const int coordinate = a.coordinate == 3 ? 3 * k_count : 3 * a.example + a.coordinate;
      factored_atoms_.push_back(p);
      map_rows_.push_back(by_weight_ ? s : coordinate);
      map_columns_.push_back(3 * (by_weight_ ? coordinate : s));
      continue;
    }
    const int column = static_cast<int>(sparse_atoms_.size());
    sparse_atoms_.push_back(p);
    for (int v = 0; v < n; ++v) {
      const double value = dictionary.value(v, p);
      if (value != 0.0) entries.emplace_back(v, column, value);
    }
  }
  sparse_.resize(n, static_cast<Eigen::Index>(sparse_atoms_.size()));
  sparse_.setFromTriplets(entries.begin(), entries.end());
}

Eigen::MatrixX3d DictionaryProduct::operator()(const Eigen::Ref<const Eigen::MatrixX3d>& t) const {
  const int n = rows();
  const auto weight_count = dense_weights_.cols();
  const Eigen::MatrixXd& multiplied = by_weight_ ? dense_weights_ : coordinates_;
  const Eigen::MatrixXd& summed = by_weight_ ? coordinates_ : dense_weights_;
  Eigen::MatrixXd maps = Eigen::MatrixXd::Zero(multiplied.cols(), 3 * summed.cols());
  for (size_t q = 0; q < factored_atoms_.size(); ++q) {
    maps.block<1, 3>(map_rows_[q], map_columns_[q]) += t.row(factored_atoms_[q]);
  }
  Eigen::MatrixX3d sparse_t(static_cast<Eigen::Index>(sparse_atoms_.size()), 3);
  for (size_t q = 0; q < sparse_atoms_.size(); ++q) sparse_t.row(static_cast<Eigen::Index>(q)) = t.row(sparse_atoms_[q]);

  Eigen::MatrixX3d result(n, 3);
  // Blocks of rows, one task each.
  const int block = 1024;
  tbb::parallel_for(0, (n + block - 1) / block, [&](int b) {
    const int first = b * block;
    const int height = std::min(block, n - first);
    auto part = result.middleRows(first, height);
    if (weight_count > 0) {
      factored_block_product(multiplied.middleRows(first, height), summed.middleRows(first, height), maps, part);
    } else {
      part.setZero();
    }
    if (!sparse_atoms_.empty()) part.noalias() += sparse_.middleRows(first, height) * sparse_t;
  });
  return result;
}

}  // namespace posekit::detail
