// The product D T of a dictionary and its transformations: the vertices at the end of every
// deformation, and the one step of it that touches every vertex.
#pragma once

#include <posekit/blend_dictionary.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace posekit::detail {

/// D T without D. Column (k, j, a) of D is w_j .* [X^k 1]_a, so D T = sum_j w_j .* ([X^1 .. X^K 1] M_j),
/// where M_j gathers the rows of T of weight j into a (3K + 1) by 3 matrix. For the weights that cover
/// most of the mesh (eigenfunctions, a constant weight) this is a product of one factor with the maps
/// summed against the other, in tiles of vertices (detail::factored_block_product): it reads
/// #V (3K + 1 + m) values where D T reads the #V N of D, and it keeps D out of memory. Atoms of
/// weights that vanish on most of the mesh (bones) are held as a row-major sparse block of D.
class DictionaryProduct {
 public:
  DictionaryProduct() = default;
  /// The split of `dictionary`: the atoms of a weight whose nonzeros are under a quarter of the
  /// vertices are held as sparse columns, the others factored.
  explicit DictionaryProduct(const BlendDictionary& dictionary);

  int rows() const { return static_cast<int>(coordinates_.rows()); }
  int cols() const { return atom_count_; }
  /// Atoms held as sparse columns.
  int sparse_atom_count() const { return static_cast<int>(sparse_atoms_.size()); }

  /// #V by 3: D T for the N by 3 transformations `t` (rows in the order of the dictionary's atoms;
  /// unchecked), vertices split over threads.
  Eigen::MatrixX3d operator()(const Eigen::Ref<const Eigen::MatrixX3d>& t) const;

 private:
  int atom_count_ = 0;
  Eigen::MatrixXd coordinates_;    // #V by 3K + 1: [X^1 .. X^K 1]
  Eigen::MatrixXd dense_weights_;  // #V by the weights held factored
  // The factor multiplied by the maps (true: dense_weights_, false: coordinates_); the other is summed.
  bool by_weight_ = false;
  std::vector<int> factored_atoms_;  // atoms of the factored weights, and where each row of T goes in
  std::vector<int> map_rows_;        // the maps: row (its weight's or its coordinate's column in the
  std::vector<int> map_columns_;     // multiplied factor) and first of three columns
  std::vector<int> sparse_atoms_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> sparse_;
};

}  // namespace posekit::detail
