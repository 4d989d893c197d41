#include <posekit/blend_dictionary.hpp>
#include <posekit/error.hpp>

#include <cmath>
#include <string>

namespace posekit {
namespace {

std::vector<DictionaryAtom> all_atoms(int example_count, int weight_count) {
  std::vector<DictionaryAtom> atoms;
  atoms.reserve(static_cast<size_t>(example_count) * weight_count * 4);
  for (int k = 0; k < example_count; ++k) {
    for (int j = 0; j < weight_count; ++j) {
      for (int a = 0; a < 4; ++a) atoms.push_back({k, j, a});
    }
  }
  return atoms;
}

void check_inputs(const std::vector<Eigen::MatrixX3d>& examples, const Eigen::MatrixXd& weights) {
  if (examples.empty()) throw ArgumentError("a blend dictionary needs at least one example pose");
  if (weights.cols() == 0) throw ArgumentError("a blend dictionary needs at least one weight function");
  for (size_t k = 0; k < examples.size(); ++k) {
    if (examples[k].rows() != weights.rows()) {
      throw ArgumentError("example " + std::to_string(k) + " has " + std::to_string(examples[k].rows()) +
                          " vertices but the weights have " + std::to_string(weights.rows()) + " rows");
    }
    if (!examples[k].allFinite()) throw ArgumentError("example " + std::to_string(k) + " has a non-finite coordinate");
  }
  if (!weights.allFinite()) throw ArgumentError("the blending weights have a non-finite value");
}

}  // namespace

BlendDictionary::BlendDictionary(std::vector<Eigen::MatrixX3d> examples, Eigen::MatrixXd weights)
    : examples_(std::move(examples)), weights_(std::move(weights)) {
  check_inputs(examples_, weights_);
  atoms_ = all_atoms(example_count(), weight_count());
}

BlendDictionary::BlendDictionary(std::vector<Eigen::MatrixX3d> examples, Eigen::MatrixXd weights,
                                 std::vector<DictionaryAtom> atoms)
    : examples_(std::move(examples)), weights_(std::move(weights)), atoms_(std::move(atoms)) {
  check_inputs(examples_, weights_);
  if (atoms_.empty()) throw ArgumentError("a blend dictionary needs at least one atom");
  for (const DictionaryAtom& a : atoms_) {
    if (a.example < 0 || a.example >= example_count() || a.weight < 0 || a.weight >= weight_count() ||
        a.coordinate < 0 || a.coordinate > 3) {
      throw ArgumentError("dictionary atom (" + std::to_string(a.example) + ", " + std::to_string(a.weight) + ", " +
                          std::to_string(a.coordinate) + ") is out of range");
    }
  }
}

Eigen::MatrixXd BlendDictionary::matrix() const {
  Eigen::MatrixXd d(vertex_count(), atom_count());
  for (int p = 0; p < atom_count(); ++p) {
    const DictionaryAtom& a = atoms_[static_cast<size_t>(p)];
    if (a.coordinate == 3) {
      d.col(p) = weights_.col(a.weight);
    } else {
      d.col(p) = weights_.col(a.weight).cwiseProduct(examples_[static_cast<size_t>(a.example)].col(a.coordinate));
    }
  }
  return d;
}

Eigen::MatrixXd BlendDictionary::rows(const std::vector<int>& vertices) const {
  Eigen::MatrixXd d(static_cast<Eigen::Index>(vertices.size()), atom_count());
  for (size_t r = 0; r < vertices.size(); ++r) {
    const int v = vertices[r];
    if (v < 0 || v >= vertex_count()) {
      throw ArgumentError("vertex " + std::to_string(v) + " is outside [0, " + std::to_string(vertex_count()) + ")");
    }
    for (int p = 0; p < atom_count(); ++p) d(static_cast<Eigen::Index>(r), p) = value(v, p);
  }
  return d;
}

Eigen::MatrixXd BlendDictionary::transformation_smoothness(const Eigen::MatrixXd& weight_smoothness) const {
  if (weight_smoothness.rows() != weight_count() || weight_smoothness.cols() != weight_count()) {
    throw ArgumentError("transformation_smoothness: the weight smoothness is " + std::to_string(weight_smoothness.rows()) +
                        " by " + std::to_string(weight_smoothness.cols()) + " for " + std::to_string(weight_count()) +
                        " weights");
  }
  Eigen::MatrixXd lambda = Eigen::MatrixXd::Zero(atom_count(), atom_count());
  for (int p = 0; p < atom_count(); ++p) {
    for (int q = 0; q < atom_count(); ++q) {
      const DictionaryAtom& a = atoms_[static_cast<size_t>(p)];
      const DictionaryAtom& b = atoms_[static_cast<size_t>(q)];
      if (a.example == b.example && a.coordinate == b.coordinate) lambda(p, q) = weight_smoothness(a.weight, b.weight);
    }
  }
  return lambda;
}

Eigen::MatrixX3d BlendDictionary::example_transformations(int example) const {
  if (example < 0 || example >= example_count()) {
    throw ArgumentError("example " + std::to_string(example) + " is outside [0, " + std::to_string(example_count()) + ")");
  }
  for (int j = 0; j < weight_count(); ++j) {
    const double value = weights_(0, j);
    if (value == 0.0 || (weights_.col(j).array() - value).abs().maxCoeff() > 1e-9 * std::abs(value)) continue;
    Eigen::MatrixX3d t = Eigen::MatrixX3d::Zero(atom_count(), 3);
    int found = 0;
    for (int p = 0; p < atom_count(); ++p) {
      const DictionaryAtom& a = atoms_[static_cast<size_t>(p)];
      if (a.weight != j || a.coordinate == 3 || a.example != example) continue;
      t(p, a.coordinate) = 1.0 / value;
      ++found;
    }
    if (found == 3) return t;
  }
  throw ArgumentError("the dictionary cannot reproduce example " + std::to_string(example) +
                      ": it keeps no constant weight function with that example's three coordinates");
}

}  // namespace posekit
