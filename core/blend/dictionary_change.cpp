#include <posekit/blend_dictionary.hpp>
#include <posekit/error.hpp>

#include <Eigen/Cholesky>

#include <string>
#include <utility>

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
  Eigen::MatrixXd cross = weighted.transpose() * from.matrix();
  // The ridge only matters where D' is rank deficient (duplicate atoms); it picks the least-norm map.
  normal.diagonal().array() += 1e-10 * normal.diagonal().mean();
  const Eigen::LLT<Eigen::MatrixXd> llt(normal);
  if (llt.info() != Eigen::Success) throw ArgumentError("DictionaryChange: the target dictionary is singular");
  llt.solveInPlace(cross);
  map_ = std::move(cross);
}

Eigen::MatrixX3d DictionaryChange::operator()(const Eigen::Ref<const Eigen::MatrixX3d>& transformations) const {
  if (transformations.rows() != map_.cols()) {
    throw ArgumentError("DictionaryChange: " + std::to_string(transformations.rows()) + " transformation rows for a "
                        "dictionary of " + std::to_string(map_.cols()) + " atoms");
  }
  return map_ * transformations;
}

}  // namespace posekit
