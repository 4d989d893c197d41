#include "reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace posekit::conformance::reference {

long double phi(long double r2) { return r2 == 0.0L ? 0.0L : 0.5L * r2 * std::log(r2); }

double squared_distance(const Points4& a, Eigen::Index i, const Points4& b, Eigen::Index j) {
  double sum = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double d = a(i, k) - b(j, k);
    sum += d * d;
  }
  return sum;
}

std::vector<long double> polynomial_basis(double x, double y, double z, double t) {
  const long double X = x, Y = y, Z = z, T = t;
  return {1.0L, X, Y, Z, T, X * X, X * Y, X * Z, X * T, Y * Y, Y * Z, Y * T, Z * Z, Z * T, T * T};
}

Assembly assemble(const Points4& points, const Points4& centers, bool with_polynomial) {
  const Eigen::Index columns = centers.rows() + (with_polynomial ? kRbfPolynomialTerms : 0);
  Assembly result{Eigen::MatrixXd(points.rows(), columns), Eigen::MatrixXd(points.rows(), columns)};
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    for (Eigen::Index j = 0; j < centers.rows(); ++j) {
      const double r2 = squared_distance(points, i, centers, j);
      const long double value = phi(r2);
      result.block(i, j) = static_cast<double>(value);
      result.magnitude(i, j) =
          static_cast<double>(std::max(std::abs(value), static_cast<long double>(r2)));
    }
    if (!with_polynomial) continue;
    const auto basis = polynomial_basis(points(i, 0), points(i, 1), points(i, 2), points(i, 3));
    for (int k = 0; k < kRbfPolynomialTerms; ++k) {
      result.block(i, centers.rows() + k) = static_cast<double>(basis[k]);
      result.magnitude(i, centers.rows() + k) = static_cast<double>(std::abs(basis[k]));
    }
  }
  return result;
}

namespace {

// f(point) in long double; magnitude receives the sum of |terms| when not null.
std::array<long double, 3> field_value(const RbfField& field, const double* point,
                                       std::array<long double, 3>* magnitude) {
  std::array<long double, 3> sum{0.0L, 0.0L, 0.0L};
  std::array<long double, 3> absolute{0.0L, 0.0L, 0.0L};
  for (Eigen::Index j = 0; j < field.centers.rows(); ++j) {
    double r2 = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double d = point[k] - field.centers(j, k);
      r2 += d * d;
    }
    const long double value = phi(r2);
    const long double scale = std::max(std::abs(value), static_cast<long double>(r2));
    for (int c = 0; c < 3; ++c) {
      sum[c] += field.weights(j, c) * value;
      absolute[c] += std::abs(static_cast<long double>(field.weights(j, c))) * scale;
    }
  }
  const auto basis = polynomial_basis(point[0], point[1], point[2], point[3]);
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < kRbfPolynomialTerms; ++k) {
      sum[c] += field.polynomial(k, c) * basis[k];
      absolute[c] += std::abs(field.polynomial(k, c) * basis[k]);
    }
  }
  if (magnitude != nullptr) *magnitude = absolute;
  return sum;
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

Evaluation evaluate(const RbfField& field, const Points4& points) {
  Evaluation result{Eigen::MatrixXd(points.rows(), 3), Eigen::MatrixXd(points.rows(), 3)};
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double point[4] = {points(i, 0), points(i, 1), points(i, 2), points(i, 3)};
    std::array<long double, 3> magnitude{};
    const auto value = field_value(field, point, &magnitude);
    for (int c = 0; c < 3; ++c) {
      result.values(i, c) = static_cast<double>(value[c]);
      result.magnitude(i, c) = static_cast<double>(magnitude[c]);
    }
  }
  return result;
}

Integration integrate(const RbfField& field, const Eigen::MatrixX3d& start,
                      const Rk45Options& options) {
  // Dormand & Prince (1980); Hairer, Norsett & Wanner, Solving ODEs I, table II.5.2.
  static const double c[7] = {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
  static const double a[7][6] = {
      {0, 0, 0, 0, 0, 0},
      {1.0 / 5, 0, 0, 0, 0, 0},
      {3.0 / 40, 9.0 / 40, 0, 0, 0, 0},
      {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0},
      {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0},
      {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0},
      {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
  static const double b5[7] = {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784,
                               11.0 / 84,  0};
  static const double b4[7] = {
      5179.0 / 57600, 0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200, 187.0 / 2100, 1.0 / 40};
  // Step-size control (kernel_math.h): safety 0.9, factor clamped to [0.2, 10], exponent -1/5,
  // no growth right after a rejection, the last step stretched by up to 1% to reach the end.
  const double safety = 0.9, min_factor = 0.2, max_factor = 10.0, stretch = 1.01;

  const auto f = [&field](const Eigen::Vector3d& x, double t) {
    const double point[4] = {x(0), x(1), x(2), t};
    const auto value = field_value(field, point, nullptr);
    return Eigen::Vector3d(static_cast<double>(value[0]), static_cast<double>(value[1]),
                           static_cast<double>(value[2]));
  };

  Integration result{start, std::vector<Rk45ParticleStats>(static_cast<std::size_t>(start.rows()))};
  for (Eigen::Index p = 0; p < start.rows(); ++p) {
    Rk45ParticleStats& stats = result.stats[static_cast<std::size_t>(p)];
    Eigen::Vector3d x = start.row(p).transpose();
    double t = options.t_begin;
    const double direction = options.t_end >= options.t_begin ? 1.0 : -1.0;
    double h = options.initial_step;
    bool previous_rejected = false;
    if (options.t_end != options.t_begin) {
      Eigen::Vector3d k[7];
      k[0] = f(x, t);
      stats.rhs_evaluations = 1;
      if (!finite(k[0])) stats.status = Rk45Status::non_finite;
      while (stats.status == Rk45Status::ok) {
        const double remaining = (options.t_end - t) * direction;
        const bool last = h * stretch >= remaining;
        const double step = direction * (last ? remaining : h);
        Eigen::Vector3d y = x;
        for (int s = 1; s < 7; ++s) {
          Eigen::Vector3d increment = Eigen::Vector3d::Zero();
          for (int j = 0; j < s; ++j) increment += a[s][j] * k[j];
          y = x + step * increment;
          k[s] = f(y, t + c[s] * step);
        }
        stats.rhs_evaluations += 6;
        const Eigen::Vector3d x_new = y;  // the last stage sits at the fifth-order solution
        if (!finite(x_new)) {
          stats.status = Rk45Status::non_finite;
          break;
        }
        Eigen::Vector3d error = Eigen::Vector3d::Zero();
        for (int j = 0; j < 7; ++j) error += (b5[j] - b4[j]) * k[j];
        error *= step;
        double sum = 0.0;
        for (int i = 0; i < 3; ++i) {
          const double scale =
              options.absolute_tolerance +
              options.relative_tolerance * std::max(std::abs(x(i)), std::abs(x_new(i)));
          sum += (error(i) / scale) * (error(i) / scale);
        }
        const double norm = std::sqrt(sum / 3.0);
        if (!std::isfinite(norm)) {
          stats.status = Rk45Status::non_finite;
          break;
        }
        if (norm <= 1.0) {
          ++stats.accepted_steps;
          x = x_new;
          k[0] = k[6];
          if (last) {
            t = options.t_end;
            break;
          }
          t += step;
          double factor =
              norm == 0.0 ? max_factor : std::min(max_factor, safety * std::pow(norm, -0.2));
          if (previous_rejected) factor = std::min(factor, 1.0);
          h = std::abs(step) * factor;
          previous_rejected = false;
        } else {
          ++stats.rejected_steps;
          h = std::abs(step) * std::max(min_factor, safety * std::pow(norm, -0.2));
          previous_rejected = true;
          if (h < options.min_step) {
            stats.status = Rk45Status::step_underflow;
            break;
          }
        }
        if (stats.accepted_steps + stats.rejected_steps >= options.max_steps) {
          stats.status = Rk45Status::max_steps;
        }
      }
    }
    result.positions.row(p) = x.transpose();
  }
  return result;
}

}  // namespace posekit::conformance::reference
