// BlendedDeformer: the local/global iterations of one deformation.
#include <posekit/error.hpp>

#include "blend/block_kernels.hpp"
#include "blend/deformer_state.hpp"
#include "blend/rotation_fit.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace posekit {
namespace {

using Clock = std::chrono::steady_clock;

// A scale cannot be negative or zero; this floor only matters for meaningless constraint sets.
constexpr double kMinimumScale = 1e-8;

double soft_threshold(double value, double threshold) {
  if (value > threshold) return value - threshold;
  if (value < -threshold) return value + threshold;
  return 0.0;
}

}  // namespace

Eigen::MatrixX3d BlendedDeformer::State::solve(const Eigen::LLT<Eigen::MatrixXd>& factor,
                                               const Eigen::Ref<const Eigen::MatrixX3d>& b) {
  Eigen::MatrixX3d x = b;
  detail::cholesky_solve(factor.matrixLLT(), x);
  return x;
}

void BlendedDeformer::State::local_step(const Eigen::Ref<const Eigen::MatrixX3d>& transformations,
                                        std::vector<Eigen::Matrix3d>& rotations,
                                        Eigen::VectorXd& dots) const {
  const int blocks = block_count();
  rotations.resize(static_cast<size_t>(blocks));
  std::vector<double> block_dots(static_cast<size_t>(blocks));
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks, 16), [&](const tbb::blocked_range<int>& range) {
    for (int j = range.begin(); j < range.end(); ++j) {
      // S = T^T G_j by dot products of contiguous columns: a general matrix product would repack G
      // (the largest array of the iteration) on every call.
      const Eigen::Matrix3d s = detail::block_product(transformations, projected.middleCols<3>(3 * j));
      const Eigen::Matrix3d r = detail::closest_rotation(s);
      rotations[static_cast<size_t>(j)] = r;
      block_dots[static_cast<size_t>(j)] = r.cwiseProduct(s).sum();
    }
  });
  dots = Eigen::VectorXd::Zero(example_count());
  for (int j = 0; j < blocks; ++j) dots(j / cluster_count) += block_dots[static_cast<size_t>(j)];
}

void BlendedDeformer::State::accumulate_blocks(int first, int last, const Eigen::Ref<const Eigen::MatrixX3d>& stacked,
                                               Eigen::MatrixX3d& side) const {
  const int rows = atom_count();
  const int chunk = std::max(32, (rows + 3) / 4);
  tbb::parallel_for(0, (rows + chunk - 1) / chunk, [&](int part) {
    const int top = part * chunk;
    const int height = std::min(chunk, rows - top);
    for (int j = first; j < last; ++j) {
      detail::accumulate_block(projected.middleCols<3>(3 * j).middleRows(top, height), stacked.middleRows<3>(3 * j),
                               side.middleRows(top, height));
    }
  });
}

Eigen::MatrixX3d BlendedDeformer::State::arap_right_side(const std::vector<Eigen::Matrix3d>& rotations,
                                                         const Eigen::VectorXd& coefficients) const {
  const int blocks = block_count();
  Eigen::MatrixX3d stacked(3 * blocks, 3);
  for (int j = 0; j < blocks; ++j) {
    stacked.middleRows<3>(3 * j) = coefficients(j / cluster_count) * rotations[static_cast<size_t>(j)].transpose();
  }
  Eigen::MatrixX3d side = Eigen::MatrixX3d::Zero(atom_count(), 3);
  // Examples of weight zero (all but one in the minimal stage) add nothing: skip their columns.
  const int k_count = example_count();
  for (int k = 0; k < k_count;) {
    if (coefficients(k) == 0.0) {
      ++k;
      continue;
    }
    int end = k + 1;
    while (end < k_count && coefficients(end) != 0.0) ++end;
    accumulate_blocks(k * cluster_count, end * cluster_count, stacked, side);
    k = end;
  }
  return side;
}

Eigen::MatrixX3d BlendedDeformer::State::initial_solve(const Eigen::Ref<const Eigen::MatrixX3d>& right_side,
                                                       double& energy) const {
  if (options.sparsity <= 0.0) {
    Eigen::MatrixX3d t = solve(initial, right_side);
    energy = -t.cwiseProduct(right_side).sum();
    return t;
  }
  // Elastic net: min t^T Q t - 2 b^T t + mu |t|_1 per column by coordinate descent on the Gram
  // matrix Q (constraints + smoothness + ridge, the quadratic part). mu >= 2 max|b| gives t = 0.
  const Eigen::MatrixXd& q = initial_matrix;
  const int n = static_cast<int>(q.rows());
  const double mu = options.sparsity * 2.0 * right_side.cwiseAbs().maxCoeff();
  Eigen::MatrixX3d t = Eigen::MatrixX3d::Zero(n, 3);
  energy = 0.0;
  for (int column = 0; column < 3; ++column) {
    Eigen::VectorXd gradient = -right_side.col(column);  // Q t - b
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    for (int sweep = 0; sweep < 1000; ++sweep) {
      double largest_change = 0.0;
      for (int p = 0; p < n; ++p) {
        const double diagonal = q(p, p);
        const double updated = soft_threshold(diagonal * x(p) - gradient(p), 0.5 * mu) / diagonal;
        const double change = updated - x(p);
        if (change == 0.0) continue;
        gradient.noalias() += change * q.col(p);
        x(p) = updated;
        largest_change = std::max(largest_change, std::abs(change) * std::sqrt(diagonal));
      }
      if (largest_change <= 1e-9 * std::sqrt(std::max(x.dot(q * x), 1e-300))) break;
    }
    t.col(column) = x;
    energy += x.dot(gradient - right_side.col(column)) + mu * x.cwiseAbs().sum();  // t^T Q t - 2 b^T t + mu|t|
  }
  return t;
}

double BlendedDeformer::State::closed_form_scale(double dot, double energy) const {
  return options.estimate_scale ? std::max(dot / energy, kMinimumScale) : 1.0;
}

namespace {

struct Iterate {
  Eigen::MatrixX3d transformations;
  std::vector<Eigen::Matrix3d> rotations;
  Eigen::VectorXd weights;
  Eigen::VectorXd scales;
  double scale = 1.0;
  int example = -1;
  double energy = std::numeric_limits<double>::infinity();
};

bool converged(double previous, double current, double tolerance) {
  return std::isfinite(previous) && previous - current <= tolerance * std::abs(previous);
}

}  // namespace

BlendResult BlendedDeformer::deform_in_own_dictionary(const Eigen::Ref<const Eigen::MatrixX3d>& targets,
                                                      bool vertices) const {
  const State& s = *state_;
  const Clock::time_point start = Clock::now();
  const Eigen::MatrixX3d p = s.internal_targets(targets);
  const Eigen::MatrixX3d weighted = s.row_weights.asDiagonal() * p;
  const Eigen::MatrixX3d constraint_side = s.rows.transpose() * weighted;
  const double constant = weighted.cwiseProduct(p).sum();
  BlendResult result;
  double initial_energy = 0.0;
  result.transformations = s.initial_solve(constraint_side, initial_energy);
  result.iterations.push_back({"initial", constant + initial_energy, 1.0, -1});
  BlendResult continued = continue_in_own_dictionary(targets, result, -1, -1, vertices);
  continued.iterations.insert(continued.iterations.begin(), result.iterations.front());
  continued.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return continued;
}

BlendResult BlendedDeformer::continue_in_own_dictionary(const Eigen::Ref<const Eigen::MatrixX3d>& targets,
                                                        const BlendResult& start_from, int average_iterations,
                                                        int minimal_iterations, bool vertices) const {
  const State& s = *state_;
  const Clock::time_point start = Clock::now();
  if (start_from.transformations.rows() != s.atom_count()) {
    throw ArgumentError("blended deformation: the start has " + std::to_string(start_from.transformations.rows()) +
                        " transformation rows for " + std::to_string(s.atom_count()) + " atoms");
  }
  const Eigen::MatrixX3d p = s.internal_targets(targets);
  const Eigen::MatrixX3d weighted = s.row_weights.asDiagonal() * p;
  const Eigen::MatrixX3d constraint_side = s.rows.transpose() * weighted;
  const double constant = weighted.cwiseProduct(p).sum();
  const int k_count = s.example_count();
  const BlendOptions& o = s.options;
  const double total_example_energy = s.example_energy.sum();

  // The global step, for fixed rotations, minimizes over the maps T and the scale s together: the
  // energy is quadratic in (T, s), with T = Q^-1 (b_c + s b_R) = T_c + s T_R, so s has a closed form
  // s = b_R.T_c / (N - b_R.T_R). Alternating s with T instead converges slowly when the scale is far
  // from 1. T_c is the same in every step.
  const Eigen::MatrixX3d constrained_maps = State::solve(s.global, constraint_side);
  struct GlobalStep {
    Eigen::MatrixX3d transformations;
    double scale = 1.0;
    double energy = 0.0;
  };
  const auto global_step = [&](const Eigen::Ref<const Eigen::MatrixX3d>& arap_side, double example_energy,
                               double fallback_scale) {
    GlobalStep step;
    const Eigen::MatrixX3d arap_maps = State::solve(s.global, arap_side);
    step.scale = 1.0;
    if (o.estimate_scale) {
      const double curvature = example_energy - arap_side.cwiseProduct(arap_maps).sum();
      const double slope = arap_side.cwiseProduct(constrained_maps).sum();
      // The curvature is positive whenever the ARAP matrix is (it is the Schur complement of the
      // joint quadratic); round-off aside, keep the alternating scale otherwise.
      step.scale = curvature > 1e-12 * example_energy ? std::max(slope / curvature, kMinimumScale) : fallback_scale;
    }
    step.transformations = constrained_maps + step.scale * arap_maps;
    const Eigen::MatrixX3d side = constraint_side + step.scale * arap_side;
    step.energy = constant + step.scale * step.scale * example_energy - step.transformations.cwiseProduct(side).sum();
    return step;
  };

  BlendResult result;
  Iterate current;
  current.transformations = start_from.transformations;
  Eigen::VectorXd dots;
  std::vector<Eigen::Matrix3d> rotations;

  double previous = std::numeric_limits<double>::infinity();
  const int average_count = average_iterations >= 0 ? average_iterations : o.average_iterations;
  const int minimal_count = minimal_iterations >= 0 ? minimal_iterations : o.minimal_iterations;
  for (int iteration = 0; iteration < average_count; ++iteration) {
    s.local_step(current.transformations, rotations, dots);
    const GlobalStep step =
        global_step(s.arap_right_side(rotations, Eigen::VectorXd::Constant(k_count, 1.0 / k_count)),
                    total_example_energy / k_count, s.closed_form_scale(dots.sum(), total_example_energy));
    const double scale = step.scale;
    current.transformations = step.transformations;
    current.energy = step.energy;
    current.rotations = rotations;
    current.weights = Eigen::VectorXd::Constant(k_count, 1.0 / k_count);
    current.scales = Eigen::VectorXd::Constant(k_count, scale);
    current.scale = scale;
    current.example = -1;
    result.iterations.push_back({"average", current.energy, scale, -1});
    if (converged(previous, current.energy, o.tolerance)) break;
    previous = current.energy;
  }

  previous = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < minimal_count; ++iteration) {
    s.local_step(current.transformations, rotations, dots);
    Eigen::VectorXd scales(k_count);
    for (int k = 0; k < k_count; ++k) {
      scales(k) = s.closed_form_scale(dots(k), s.example_energy(k));
    }
    // Block coordinate descent on the minimal energy: for the current maps, the example (with its
    // rotations and scale) of the least ARAP energy s^2 N_k - 2 s <R, S> + (a term common to all
    // examples), then the global step for that example alone.
    int best = 0;
    double best_arap = std::numeric_limits<double>::infinity();
    for (int k = 0; k < k_count; ++k) {
      const double arap = scales(k) * (scales(k) * s.example_energy(k) - 2.0 * dots(k));
      if (arap < best_arap) {
        best_arap = arap;
        best = k;
      }
    }
    if (o.example_choice_after_solve) {
      // The example of the least energy after its own global step: with Q = L L^T the minimum over
      // (T, s) is c - |f_c + s f_k|^2 + s^2 N_k, f = L^-1 b, one forward substitution per example.
      Eigen::MatrixXd sides(s.atom_count(), 3 * (k_count + 1));
      sides.leftCols<3>() = constraint_side;
      for (int k = 0; k < k_count; ++k) {
        Eigen::VectorXd only = Eigen::VectorXd::Zero(k_count);
        only(k) = 1.0;
        sides.middleCols<3>(3 * (k + 1)) = s.arap_right_side(rotations, only);
      }
      s.global.matrixL().solveInPlace(sides);
      const auto f_c = sides.leftCols<3>();
      double lowest = std::numeric_limits<double>::infinity();
      for (int k = 0; k < k_count; ++k) {
        const auto f_k = sides.middleCols<3>(3 * (k + 1));
        const double curvature = s.example_energy(k) - f_k.squaredNorm();
        double scale = scales(k);
        if (o.estimate_scale && curvature > 1e-12 * s.example_energy(k)) {
          scale = std::max(f_c.cwiseProduct(f_k).sum() / curvature, kMinimumScale);
        }
        const double energy = scale * scale * s.example_energy(k) - (f_c + scale * f_k).squaredNorm();
        if (energy < lowest) {
          lowest = energy;
          best = k;
        }
      }
    }
    Eigen::VectorXd one_hot = Eigen::VectorXd::Zero(k_count);
    one_hot(best) = 1.0;
    const GlobalStep step = global_step(s.arap_right_side(rotations, one_hot), s.example_energy(best), scales(best));
    scales(best) = step.scale;
    const double best_energy = step.energy;
    current.transformations = step.transformations;
    current.energy = best_energy;
    current.rotations = rotations;
    current.weights = Eigen::VectorXd::Zero(k_count);
    current.weights(best) = 1.0;
    current.scales = scales;
    current.scale = scales(best);
    current.example = best;
    result.iterations.push_back({"minimal", best_energy, scales(best), best});
    if (converged(previous, best_energy, o.tolerance)) break;
    previous = best_energy;
  }

  if (current.rotations.empty()) {
    // No iteration ran: rotations and scale of the starting transformations, for interpolation.
    s.local_step(current.transformations, current.rotations, dots);
    current.scale = s.closed_form_scale(dots.sum(), total_example_energy);
    current.weights = Eigen::VectorXd::Constant(k_count, 1.0 / k_count);
    current.scales = Eigen::VectorXd::Constant(k_count, current.scale);
    current.energy = start_from.iterations.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                   : start_from.iterations.back().energy;
  }
  result.targets = targets;
  result.transformations = current.transformations;
  result.rotations = std::move(current.rotations);
  result.example_weights = current.weights;
  result.example_scales = current.scales;
  result.scale = current.scale;
  result.closest_example = current.example;
  result.energy = current.energy;
  if (vertices) result.vertices = own_vertices(result.transformations);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

BlendResult BlendedDeformer::deform(const Eigen::Ref<const Eigen::MatrixX3d>& targets) const {
  const State& s = *state_;
  if (!s.richer) return deform_in_own_dictionary(targets);
  // The paper's schedule for articulated shapes: the smooth Laplace-Beltrami dictionary finds the
  // pose, the skeleton dictionary (least squares change, then its own iterations) its stiff parts.
  const Clock::time_point start = Clock::now();
  const BlendResult first = deform_in_own_dictionary(targets, false);
  BlendResult seed;
  seed.transformations = (*s.change)(first.transformations);
  seed.iterations = first.iterations;
  BlendResult result = s.richer->deform(targets, seed);
  for (BlendIteration& it : result.iterations) it.stage = "skeleton " + it.stage;
  result.iterations.insert(result.iterations.begin(), first.iterations.begin(), first.iterations.end());
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

BlendResult BlendedDeformer::deform(const Eigen::Ref<const Eigen::MatrixX3d>& targets, const BlendResult& start_from,
                                    int average_iterations, int minimal_iterations) const {
  const State& s = *state_;
  if (s.richer) return s.richer->deform(targets, start_from, average_iterations, minimal_iterations);
  return continue_in_own_dictionary(targets, start_from, average_iterations, minimal_iterations);
}

}  // namespace posekit
