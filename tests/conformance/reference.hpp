// The plain reference every backend is compared with: scalar loops, std::log, long double sums,
// and an RK45 driver written from the textbook, independent of kernel_math.h. Slow and obvious
// on purpose.
#pragma once

#include <posekit/device.hpp>

#include <Eigen/Core>

#include <vector>

namespace posekit::conformance::reference {

/// phi(r) = r^2 ln r from r2 = r^2, with phi(0) = 0, in long double.
long double phi(long double r2);

/// |a - b|^2 for two rows of points, from coordinate differences.
double squared_distance(const Points4& a, Eigen::Index i, const Points4& b, Eigen::Index j);

/// The 15 polynomial terms at a point, in the documented order (1, x, y, z, t, x^2, xy, ...).
std::vector<long double> polynomial_basis(double x, double y, double z, double t);

/// An assembled block and, per entry, the scale its tolerance refers to (max(|phi|, r^2) for a
/// kernel entry, |term| for a polynomial entry).
struct Assembly {
  Eigen::MatrixXd block;
  Eigen::MatrixXd magnitude;
};
Assembly assemble(const Points4& points, const Points4& centers, bool with_polynomial);

/// Field values at points (#P by 3) and, per entry, the sum of the absolute values of the terms
/// (|w_j| max(|phi_j|, r_j^2) and |p_k pi_k|).
struct Evaluation {
  Eigen::MatrixXd values;
  Eigen::MatrixXd magnitude;
};
Evaluation evaluate(const RbfField& field, const Points4& points);

/// End positions and statistics of the adaptive Dormand-Prince 5(4) integration of every row of
/// `start`, with the step-size control documented in kernel_math.h.
struct Integration {
  Eigen::MatrixX3d positions;
  std::vector<Rk45ParticleStats> stats;
};
Integration integrate(const RbfField& field, const Eigen::MatrixX3d& start,
                      const Rk45Options& options);

}  // namespace posekit::conformance::reference
