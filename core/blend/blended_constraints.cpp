// BlendedDeformer: the constraint set and the two factorizations that depend on it. Adding,
// removing or replacing one constraint changes both matrices by a rank-one term alpha w r^T r, which
// Eigen's LLT applies to the Cholesky factor in O(N^2) instead of refactorizing in O(N^3).
#include <posekit/error.hpp>

#include "blend/deformer_state.hpp"

#include <cmath>
#include <string>

namespace posekit {
namespace {

void factorize(Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::MatrixXd& matrix, const char* which) {
  llt.compute(matrix);
  if (llt.info() != Eigen::Success) {
    throw ArgumentError(std::string("blended deformation: the ") + which + " matrix is not positive definite");
  }
}

}  // namespace

Eigen::RowVectorXd BlendedDeformer::State::constraint_row(const LinearConstraint& constraint) const {
  const int vertex_count = static_cast<int>(product.rows());
  if (constraint.vertices.empty()) throw ArgumentError("a linear constraint names no vertex");
  if (constraint.vertices.size() != constraint.coefficients.size()) {
    throw ArgumentError("a linear constraint has " + std::to_string(constraint.vertices.size()) + " vertices but " +
                        std::to_string(constraint.coefficients.size()) + " coefficients");
  }
  if (!(constraint.weight > 0.0) || !std::isfinite(constraint.weight)) {
    throw ArgumentError("a linear constraint has weight " + std::to_string(constraint.weight) +
                        "; it must be finite and positive");
  }
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(product.cols());
  for (size_t i = 0; i < constraint.vertices.size(); ++i) {
    const int v = constraint.vertices[i];
    if (v < 0 || v >= vertex_count) {
      throw ArgumentError("constraint vertex " + std::to_string(v) + " is outside [0, " + std::to_string(vertex_count) + ")");
    }
    if (!std::isfinite(constraint.coefficients[i])) throw ArgumentError("a linear constraint has a non-finite coefficient");
    row += constraint.coefficients[i] * dictionary.rows({v}).row(0);
  }
  return row;
}

Eigen::MatrixX3d BlendedDeformer::State::internal_targets(const Eigen::Ref<const Eigen::MatrixX3d>& targets) const {
  if (constraints.empty()) throw ArgumentError("blended deformation: no constraint is set");
  if (targets.rows() != static_cast<Eigen::Index>(constraints.size())) {
    throw ArgumentError("blended deformation: " + std::to_string(targets.rows()) + " targets for " +
                        std::to_string(constraints.size()) + " constraints");
  }
  for (Eigen::Index r = 0; r < targets.rows(); ++r) {
    if (!targets.row(r).allFinite()) {
      throw ArgumentError("blended deformation: the target of constraint " + std::to_string(r) + " is not finite");
    }
  }
  return (targets.rowwise() - center) * scale;
}

void BlendedDeformer::State::rank_update(const Eigen::RowVectorXd& row, double sigma) {
  const Eigen::VectorXd column = row.transpose();
  initial_matrix.noalias() += sigma * column * row;
  global_matrix.noalias() += sigma * column * row;
  initial.rankUpdate(column, sigma);
  global.rankUpdate(column, sigma);
  // A downdate can lose positive definiteness to round-off; start those factors afresh.
  if (initial.info() != Eigen::Success) factorize(initial, initial_matrix, "initial");
  if (global.info() != Eigen::Success) factorize(global, global_matrix, "global");
}

void BlendedDeformer::set_constraints(const std::vector<LinearConstraint>& constraints) {
  State& s = *state_;
  if (constraints.empty()) throw ArgumentError("blended deformation needs at least one constraint");
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(constraints.size()), s.atom_count());
  Eigen::VectorXd weights(rows.rows());
  for (size_t r = 0; r < constraints.size(); ++r) {
    rows.row(static_cast<Eigen::Index>(r)) = s.constraint_row(constraints[r]);
    weights(static_cast<Eigen::Index>(r)) = s.options.constraint_weight * constraints[r].weight;
  }
  const Eigen::MatrixXd gram = rows.transpose() * weights.asDiagonal() * rows;
  Eigen::MatrixXd initial_matrix = s.base_initial + gram;
  Eigen::MatrixXd global_matrix = s.base_global + gram;
  Eigen::LLT<Eigen::MatrixXd> initial;
  Eigen::LLT<Eigen::MatrixXd> global;
  factorize(initial, initial_matrix, "initial");
  factorize(global, global_matrix, "global");
  s.constraints = constraints;
  s.rows = std::move(rows);
  s.row_weights = std::move(weights);
  s.initial_matrix = std::move(initial_matrix);
  s.global_matrix = std::move(global_matrix);
  s.initial = std::move(initial);
  s.global = std::move(global);
  if (s.richer) s.richer->set_constraints(constraints);
}

void BlendedDeformer::add_constraint(const LinearConstraint& constraint) {
  State& s = *state_;
  if (s.constraints.empty()) {
    set_constraints({constraint});
    return;
  }
  const Eigen::RowVectorXd row = s.constraint_row(constraint);
  const double weight = s.options.constraint_weight * constraint.weight;
  s.rank_update(row, weight);
  s.constraints.push_back(constraint);
  s.rows.conservativeResize(s.rows.rows() + 1, Eigen::NoChange);
  s.rows.bottomRows(1) = row;
  s.row_weights.conservativeResize(s.row_weights.size() + 1);
  s.row_weights(s.row_weights.size() - 1) = weight;
  if (s.richer) s.richer->add_constraint(constraint);
}

void BlendedDeformer::remove_constraint(int index) {
  State& s = *state_;
  const int count = constraint_count();
  if (index < 0 || index >= count) {
    throw ArgumentError("constraint " + std::to_string(index) + " is outside [0, " + std::to_string(count) + ")");
  }
  if (count == 1) throw ArgumentError("cannot remove the last constraint; set new ones instead");
  s.rank_update(s.rows.row(index), -s.row_weights(index));
  const Eigen::Index tail = count - index - 1;
  s.rows.middleRows(index, tail) = s.rows.bottomRows(tail).eval();
  s.rows.conservativeResize(count - 1, Eigen::NoChange);
  s.row_weights.segment(index, tail) = s.row_weights.tail(tail).eval();
  s.row_weights.conservativeResize(count - 1);
  s.constraints.erase(s.constraints.begin() + index);
  if (s.richer) s.richer->remove_constraint(index);
}

void BlendedDeformer::replace_constraint(int index, const LinearConstraint& constraint) {
  State& s = *state_;
  const int count = constraint_count();
  if (index < 0 || index >= count) {
    throw ArgumentError("constraint " + std::to_string(index) + " is outside [0, " + std::to_string(count) + ")");
  }
  const Eigen::RowVectorXd row = s.constraint_row(constraint);
  const double weight = s.options.constraint_weight * constraint.weight;
  // Update before downdating, so the matrix stays safely positive definite in between.
  s.rank_update(row, weight);
  s.rank_update(s.rows.row(index), -s.row_weights(index));
  s.rows.row(index) = row;
  s.row_weights(index) = weight;
  s.constraints[static_cast<size_t>(index)] = constraint;
  if (s.richer) s.richer->replace_constraint(index, constraint);
}

int BlendedDeformer::constraint_count() const { return static_cast<int>(state_->constraints.size()); }

const std::vector<LinearConstraint>& BlendedDeformer::constraints() const { return state_->constraints; }

}  // namespace posekit
