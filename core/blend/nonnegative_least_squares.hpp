// Small non-negative least squares in normal-equation form: the per-vertex weight solve of the
// skinning decomposition (a handful of unknowns, solved millions of times).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <vector>

namespace posekit::detail {

/// Minimizes 1/2 w^T G w - h^T w over w >= 0 for a symmetric positive definite G (n by n, small), by
/// Lawson and Hanson's active-set method: unknowns enter the free set one at a time by the largest
/// descent, and the step back to the feasible region drops those that reach zero.
inline Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& g, const Eigen::VectorXd& h) {
  const int n = static_cast<int>(h.size());
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
  std::vector<char> free_set(static_cast<size_t>(n), 0);
  const double tolerance = 1e-12 * std::max(1.0, h.cwiseAbs().maxCoeff());
  const auto solve_free = [&](Eigen::VectorXd& z) {
    std::vector<int> index;
    for (int j = 0; j < n; ++j) {
      if (free_set[static_cast<size_t>(j)]) index.push_back(j);
    }
    const int m = static_cast<int>(index.size());
    Eigen::MatrixXd sub(m, m);
    Eigen::VectorXd rhs(m);
    for (int a = 0; a < m; ++a) {
      rhs(a) = h(index[static_cast<size_t>(a)]);
      for (int b = 0; b < m; ++b) sub(a, b) = g(index[static_cast<size_t>(a)], index[static_cast<size_t>(b)]);
    }
    const Eigen::VectorXd solution = sub.ldlt().solve(rhs);
    z.setZero(n);
    for (int a = 0; a < m; ++a) z(index[static_cast<size_t>(a)]) = solution(a);
  };
  for (int outer = 0; outer < 3 * n + 3; ++outer) {
    const Eigen::VectorXd descent = h - g * w;
    int enter = -1;
    double largest = tolerance;
    for (int j = 0; j < n; ++j) {
      if (!free_set[static_cast<size_t>(j)] && descent(j) > largest) {
        largest = descent(j);
        enter = j;
      }
    }
    if (enter < 0) break;
    free_set[static_cast<size_t>(enter)] = 1;
    Eigen::VectorXd z;
    for (int inner = 0; inner <= n; ++inner) {
      solve_free(z);
      bool feasible = true;
      double step = 1.0;
      for (int j = 0; j < n; ++j) {
        if (free_set[static_cast<size_t>(j)] && z(j) <= 0.0) {
          feasible = false;
          const double denominator = w(j) - z(j);
          if (denominator > 0.0) step = std::min(step, w(j) / denominator);
        }
      }
      if (feasible) {
        w = z;
        break;
      }
      w += step * (z - w);
      for (int j = 0; j < n; ++j) {
        if (free_set[static_cast<size_t>(j)] && w(j) <= 1e-14) {
          free_set[static_cast<size_t>(j)] = 0;
          w(j) = 0.0;
        }
      }
    }
  }
  return w;
}

}  // namespace posekit::detail
