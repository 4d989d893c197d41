#include <posekit/blend_dictionary.hpp>
#include <posekit/error.hpp>

#include <Eigen/Cholesky>

#include <string>

namespace posekit {

DictionaryChange::DictionaryChange(const BlendDictionary& from, const BlendDictionary& to, const Eigen::VectorXd& mass) {
  if (from.vertex_count() != to.vertex_count() || mass.size() != to.vertex_count()) {
    throw ArgumentError("DictionaryChange: the dictionaries have " + std::to_string(from.vertex_count()) + " and " +
                        std::to_string(to.vertex_count()) + " vertices and the mass " + std::to_string(mass.size()));
  }
  if (!(mass.array() > 0.0).all()) throw ArgumentError("DictionaryChange: every mass must be positive");
  const Eigen::MatrixXd target = to.matrix();
  const Eigen::MatrixXd weighted = mass.asDiagonal() * target;
  Eigen::MatrixXd normal = weighted.transpose() * target;
  cross_ = weighted.transpose() * from.matrix();
  // The ridge only matters where D' is rank deficient (duplicate atoms); it picks the least-norm map.
  normal.diagonal().array() += 1e-10 * normal.diagonal().mean();
  Eigen::LLT<Eigen::MatrixXd> llt(normal);
  if (llt.info() != Eigen::Success) throw ArgumentError("DictionaryChange: the target dictionary is singular");
  factor_ = llt.matrixL();
}

Eigen::MatrixX3d DictionaryChange::operator()(const Eigen::Ref<const Eigen::MatrixX3d>& transformations) const {
  if (transformations.rows() != cross_.cols()) {
    throw ArgumentError("DictionaryChange: " + std::to_string(transformations.rows()) + " transformation rows for a "
                        "dictionary of " + std::to_string(cross_.cols()) + " atoms");
  }
  Eigen::MatrixX3d result = cross_ * transformations;
  factor_.triangularView<Eigen::Lower>().solveInPlace(result);
  factor_.triangularView<Eigen::Lower>().transpose().solveInPlace(result);
  return result;
}

}  // namespace posekit
