// The example-based dictionary of blended transformations: from K example poses X^1..X^K of one
// connectivity and m blending weight functions w_1..w_m, the n by 4mK matrix D whose column
// (k, j, a) is w_j .* [X^k 1]_a. A pose is D T for a 4mK by 3 matrix T of stacked affine maps:
// x_i = sum_k sum_j w_j(i) [x^k_i 1] T_jk. Reduction keeps a subset of the columns (k-medoids);
// a change of dictionary carries a pose from one dictionary to another by least squares.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace posekit {

/// One column of a dictionary: weight function `weight` times coordinate `coordinate` of example
/// `example` (coordinate 0, 1, 2 for x, y, z; 3 for the constant 1 of homogeneous coordinates).
struct DictionaryAtom {
  int example = 0;
  int weight = 0;
  int coordinate = 0;
  bool operator==(const DictionaryAtom& other) const {
    return example == other.example && weight == other.weight && coordinate == other.coordinate;
  }
};

/// A dictionary: the example poses, the weights and the atoms (columns) it uses.
class BlendDictionary {
 public:
  BlendDictionary() = default;
  /// The full dictionary of K = examples.size() poses (each #V by 3) and the #V by m `weights`:
  /// all 4mK atoms, ordered by example, then weight, then coordinate. Throws ArgumentError when there
  /// is no example, the sizes disagree or a value is not finite.
  BlendDictionary(std::vector<Eigen::MatrixX3d> examples, Eigen::MatrixXd weights);
  /// The same poses and weights with only the listed atoms (each within range; throws ArgumentError
  /// otherwise or when `atoms` is empty).
  BlendDictionary(std::vector<Eigen::MatrixX3d> examples, Eigen::MatrixXd weights, std::vector<DictionaryAtom> atoms);

  int vertex_count() const { return static_cast<int>(weights_.rows()); }
  int weight_count() const { return static_cast<int>(weights_.cols()); }
  int example_count() const { return static_cast<int>(examples_.size()); }
  int atom_count() const { return static_cast<int>(atoms_.size()); }
  const std::vector<DictionaryAtom>& atoms() const { return atoms_; }
  const std::vector<Eigen::MatrixX3d>& examples() const { return examples_; }
  const Eigen::MatrixXd& weights() const { return weights_; }

  /// Value of atom `atom` at vertex `vertex` (both unchecked).
  double value(int vertex, int atom) const {
    const DictionaryAtom& a = atoms_[static_cast<size_t>(atom)];
    const double coordinate = a.coordinate == 3 ? 1.0 : examples_[static_cast<size_t>(a.example)](vertex, a.coordinate);
    return weights_(vertex, a.weight) * coordinate;
  }
  /// The #V by atom_count() matrix D.
  Eigen::MatrixXd matrix() const;
  /// The rows of D at the listed vertices (each in [0, #V); throws ArgumentError otherwise).
  Eigen::MatrixXd rows(const std::vector<int>& vertices) const;
  /// atom_count() by atom_count() smoothness of the transformations: entry (p, q) is
  /// weight_smoothness(w_p, w_q) when atoms p and q share example and coordinate, 0 otherwise, so that
  /// tr(T^T Lambda T) sums the smoothness of every blended map entry. `weight_smoothness` is m by m.
  Eigen::MatrixXd transformation_smoothness(const Eigen::MatrixXd& weight_smoothness) const;
  /// The atom_count() by 3 transformations that reproduce example `example` exactly (identity maps
  /// on the constant weight function): needs a constant weight, i.e. a column of `weights` with equal
  /// entries that the dictionary keeps with all four coordinates of the example. Throws ArgumentError
  /// otherwise.
  Eigen::MatrixX3d example_transformations(int example) const;

 private:
  std::vector<Eigen::MatrixX3d> examples_;
  Eigen::MatrixXd weights_;
  std::vector<DictionaryAtom> atoms_;
};

/// Reduces `dictionary` to `atom_count` atoms by k-medoids clustering of its atoms: the distance of
/// two atoms is 1 - |cos| of the angle between them under the #V `mass` inner product (atoms that are
/// multiples of each other coincide), and each cluster keeps its medoid, one of the original atoms.
/// Deterministic (farthest-first initialization). The atoms listed in `keep` (indices into the
/// dictionary's atoms) are fixed medoids, always kept. The Gram matrix is taken over at most
/// `sample_vertices` vertices spread by index. keep.size() <= atom_count; a count at or above the
/// dictionary's size returns it unchanged. Throws ArgumentError on bad sizes or indices.
BlendDictionary reduce_dictionary(const BlendDictionary& dictionary, int atom_count, const Eigen::VectorXd& mass,
                                  const std::vector<int>& keep = {}, int sample_vertices = 4000);

/// Carries transformations from one dictionary to another of the same vertex count by weighted least
/// squares, T' = (D'^T M D')^-1 D'^T M D T (the paper's D'^+ D T with the mass matrix M as inner
/// product, plus a ridge of 1e-10 of the mean diagonal for rank-deficient D'). Forms the map once.
class DictionaryChange {
 public:
  /// `from` and `to` share #V; `mass` has #V positive entries. Throws ArgumentError otherwise.
  DictionaryChange(const BlendDictionary& from, const BlendDictionary& to, const Eigen::VectorXd& mass);
  /// from.atom_count() by 3 transformations -> to.atom_count() by 3.
  Eigen::MatrixX3d operator()(const Eigen::Ref<const Eigen::MatrixX3d>& transformations) const;

 private:
  // (D'^T M D' + ridge)^-1 D'^T M D, formed once: a change is then one product, where solving with
  // the Cholesky factor on every call cost several times as much.
  Eigen::MatrixXd map_;
};

}  // namespace posekit
