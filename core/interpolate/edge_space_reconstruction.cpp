#include "interpolate/edge_space_reconstruction.hpp"

#include <posekit/edge_space.hpp>
#include <posekit/error.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace posekit::interpolation {
namespace {

// Damps Gauss-Newton steps along the free rigid motion (and very soft modes).
constexpr double kRegularization = 1e-8;
constexpr int kLineSearchSteps = 8;

// The first vertex of every edge-connected piece of the patch: pinning it fixes the free translation
// without pulling the shape.
std::vector<int> connected_piece_starts(const EdgeSpacePatch& patch) {
  const int vertex_count = patch.vertex_count();
  std::vector<std::vector<int>> adjacent(static_cast<size_t>(vertex_count));
  for (int e = 0; e < patch.edge_count(); ++e) {
    adjacent[static_cast<size_t>(patch.edges(e, 0))].push_back(patch.edges(e, 1));
    adjacent[static_cast<size_t>(patch.edges(e, 1))].push_back(patch.edges(e, 0));
  }
  std::vector<char> reached(static_cast<size_t>(vertex_count), 0);
  std::vector<int> starts;
  std::vector<int> stack;
  for (int start = 0; start < vertex_count; ++start) {
    if (reached[static_cast<size_t>(start)]) continue;
    reached[static_cast<size_t>(start)] = 1;
    starts.push_back(start);
    stack.assign(1, start);
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (const int w : adjacent[static_cast<size_t>(v)]) {
        if (reached[static_cast<size_t>(w)]) continue;
        reached[static_cast<size_t>(w)] = 1;
        stack.push_back(w);
      }
    }
  }
  return starts;
}

}  // namespace

EdgeSpaceReconstruction::EdgeSpaceReconstruction(EdgeSpacePatch patch,
                                                 const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                                 const PoseDeformations& deformations)
    : patch_(std::move(patch)) {
  const int face_count = patch_.face_count();
  const int vertex_count = patch_.vertex_count();
  Eigen::MatrixX3d local(vertex_count, 3);
  for (int v = 0; v < vertex_count; ++v) local.row(v) = reference.row(patch_.vertices[static_cast<size_t>(v)]);

  // Gradient-space start: the cotangent Laplacian of pose 0, factorized once.
  gradients_.resize(static_cast<size_t>(face_count));
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(face_count) * 9 + static_cast<size_t>(vertex_count));
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(vertex_count);
  for (int f = 0; f < face_count; ++f) {
    FaceGradient& g = gradients_[static_cast<size_t>(f)];
    const Eigen::Vector3d a = local.row(patch_.faces(f, 0));
    const Eigen::Vector3d b = local.row(patch_.faces(f, 1));
    const Eigen::Vector3d c = local.row(patch_.faces(f, 2));
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double twice_area = cross.norm();
    if (!(twice_area > 0.0)) continue;  // a degenerate face constrains nothing
    g.area = 0.5 * twice_area;
    const Eigen::Vector3d normal = cross / twice_area;
    g.hat_gradients.col(0) = normal.cross(c - b) / twice_area;
    g.hat_gradients.col(1) = normal.cross(a - c) / twice_area;
    g.hat_gradients.col(2) = normal.cross(b - a) / twice_area;
    Eigen::Matrix3d corners;
    corners << a.transpose(), b.transpose(), c.transpose();
    g.coordinates = g.hat_gradients * corners;
    const Eigen::Matrix3d stiffness = g.area * g.hat_gradients.transpose() * g.hat_gradients;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) entries.emplace_back(patch_.faces(f, i), patch_.faces(f, j), stiffness(i, j));
      diagonal(patch_.faces(f, i)) += stiffness(i, i);
    }
  }
  const double pin = vertex_count > 0 && diagonal.mean() > 0.0 ? diagonal.mean() : 1.0;
  for (const int v : connected_piece_starts(patch_)) entries.emplace_back(v, v, pin);
  for (int v = 0; v < vertex_count; ++v) {
    // A vertex of degenerate faces only would leave the matrix singular.
    if (!(diagonal(v) > 0.0)) entries.emplace_back(v, v, pin);
  }
  Eigen::SparseMatrix<double> cotangent(vertex_count, vertex_count);
  cotangent.setFromTriplets(entries.begin(), entries.end());
  gradient_solver_.compute(cotangent);
  if (gradient_solver_.info() != Eigen::Success) throw Error("edge-space reconstruction: the Poisson factorization failed");
  for (size_t k = 0; k < deformations.logs.size(); ++k) {
    std::vector<Eigen::Vector3d> logs(static_cast<size_t>(face_count));
    std::vector<Eigen::Matrix3d> stretches(static_cast<size_t>(face_count));
    for (int f = 0; f < face_count; ++f) {
      const auto mesh_face = static_cast<size_t>(patch_.mesh_faces[static_cast<size_t>(f)]);
      logs[static_cast<size_t>(f)] = deformations.logs[k][mesh_face];
      stretches[static_cast<size_t>(f)] = deformations.stretches[k][mesh_face];
    }
    logs_.push_back(std::move(logs));
    stretches_.push_back(std::move(stretches));
  }

}

void EdgeSpaceReconstruction::prepare_gauss_newton() {
  if (gauss_newton_ready_) return;
  // Normal equations: blocks for edges and for the four corners of every hinge.
  std::vector<std::pair<int, int>> vertex_pairs;
  vertex_pairs.reserve(static_cast<size_t>(patch_.edge_count()) + patch_.hinges.size());
  for (int e = 0; e < patch_.edge_count(); ++e) vertex_pairs.emplace_back(patch_.edges(e, 0), patch_.edges(e, 1));
  for (const Hinge& h : patch_.hinges) vertex_pairs.emplace_back(h.c, h.d);
  normal_matrix_ = BlockSparseMatrix3(patch_.vertex_count(), vertex_pairs);
  edge_slots_.reserve(2 * static_cast<size_t>(patch_.edge_count()));
  for (int e = 0; e < patch_.edge_count(); ++e) {
    edge_slots_.push_back(normal_matrix_.slot(patch_.edges(e, 0), patch_.edges(e, 1)));
    edge_slots_.push_back(normal_matrix_.slot(patch_.edges(e, 1), patch_.edges(e, 0)));
  }
  hinge_slots_.reserve(patch_.hinges.size() * 16);
  for (const Hinge& h : patch_.hinges) {
    const int corners[4] = {h.a, h.b, h.c, h.d};
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) hinge_slots_.push_back(normal_matrix_.slot(corners[i], corners[j]));
    }
  }
  normal_solver_.analyze_pattern(normal_matrix_.matrix());
  gauss_newton_ready_ = true;
}

Eigen::MatrixX3d EdgeSpaceReconstruction::gradient_guess(const Eigen::VectorXd& weights) const {
  const int face_count = patch_.face_count();
  const int vertex_count = patch_.vertex_count();
  if (weights.size() != static_cast<Eigen::Index>(logs_.size()) + 1) {
    throw ArgumentError("edge-space reconstruction: " + std::to_string(weights.size()) + " weights for " +
                        std::to_string(logs_.size() + 1) + " poses");
  }
  std::vector<Eigen::Matrix3d> contributions(static_cast<size_t>(face_count));
  tbb::parallel_for(0, face_count, [&](int f) {
    const FaceGradient& g = gradients_[static_cast<size_t>(f)];
    Eigen::Vector3d log = Eigen::Vector3d::Zero();
    Eigen::Matrix3d stretch = weights(0) * Eigen::Matrix3d::Identity();
    for (size_t k = 0; k < logs_.size(); ++k) {
      log += weights(static_cast<Eigen::Index>(k) + 1) * logs_[k][static_cast<size_t>(f)];
      stretch += weights(static_cast<Eigen::Index>(k) + 1) * stretches_[k][static_cast<size_t>(f)];
    }
    const double angle = log.norm();
    const Eigen::Matrix3d rotation =
        angle > 0.0 ? Eigen::AngleAxisd(angle, log / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    // The blended deformation applied to the face's own pose-0 gradients.
    contributions[static_cast<size_t>(f)] =
        g.area * g.hat_gradients.transpose() * g.coordinates * (rotation * stretch).transpose();
  });
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(vertex_count, 3);
  for (int f = 0; f < face_count; ++f) {
    for (int corner = 0; corner < 3; ++corner) rhs.row(patch_.faces(f, corner)) += contributions[static_cast<size_t>(f)].row(corner);
  }
  Eigen::MatrixX3d x(vertex_count, 3);
  for (int c = 0; c < 3; ++c) x.col(c) = gradient_solver_.solve(rhs.col(c));
  return x;
}

double EdgeSpaceReconstruction::energy(const Eigen::Ref<const Eigen::MatrixX3d>& x, const Eigen::VectorXd& lengths,
                                       const Eigen::VectorXd& angles, double bending_weight) const {
  double sum = 0.0;
  for (int e = 0; e < patch_.edge_count(); ++e) {
    const double target = lengths(e);
    const double r = ((x.row(patch_.edges(e, 1)) - x.row(patch_.edges(e, 0))).norm() - target) / target;
    sum += r * r;
  }
  for (int index = 0; index < patch_.hinge_count(); ++index) {
    const double r = wrap_angle(hinge_angle(patch_.hinges[static_cast<size_t>(index)], x) - angles(index));
    sum += bending_weight * r * r;
  }
  return sum;
}

ReconstructionStats EdgeSpaceReconstruction::refine(Eigen::MatrixX3d& x, const Eigen::VectorXd& target_lengths,
                                                    const Eigen::VectorXd& angles, const ReconstructionOptions& options) {
  const int vertex_count = patch_.vertex_count();
  const int edge_count = patch_.edge_count();
  const int hinge_count = patch_.hinge_count();
  if (target_lengths.size() != edge_count || angles.size() != hinge_count || x.rows() != vertex_count) {
    throw ArgumentError("edge-space reconstruction: " + std::to_string(target_lengths.size()) + " lengths and " +
                        std::to_string(angles.size()) + " angles for " + std::to_string(edge_count) + " edges and " +
                        std::to_string(hinge_count) + " hinges");
  }
  // Extrapolated weights may ask for lengths at or below zero; a tiny positive floor keeps the fit defined.
  const double floor = 1e-12 * std::max(target_lengths.cwiseAbs().maxCoeff(), 1e-300);
  const Eigen::VectorXd lengths = target_lengths.cwiseMax(floor);
  const double mu = options.bending_weight;
  ReconstructionStats stats;
  double current = energy(x, lengths, angles, mu);
  stats.initial_energy = current;
  if (options.max_iterations > 0) prepare_gauss_newton();
  std::vector<Eigen::Matrix<double, 4, 3>> gradients(static_cast<size_t>(hinge_count));
  std::vector<double> residuals(static_cast<size_t>(hinge_count));
  for (int iteration = 0; iteration < options.max_iterations && current > 0.0; ++iteration) {
    normal_matrix_.set_zero();
    Eigen::VectorXd gradient = Eigen::VectorXd::Zero(3 * vertex_count);
    for (int e = 0; e < edge_count; ++e) {
      const int a = patch_.edges(e, 0);
      const int b = patch_.edges(e, 1);
      const Eigen::Vector3d vector = x.row(b) - x.row(a);
      const double length = vector.norm();
      if (!(length > 0.0)) continue;
      const Eigen::Vector3d j = vector / (length * lengths(e));  // d r / d x_b
      const double r = (length - lengths(e)) / lengths(e);
      const Eigen::Matrix3d block = j * j.transpose();
      normal_matrix_.add(normal_matrix_.diagonal_slot(a), block);
      normal_matrix_.add(normal_matrix_.diagonal_slot(b), block);
      normal_matrix_.add(edge_slots_[2 * static_cast<size_t>(e)], -block);
      normal_matrix_.add(edge_slots_[2 * static_cast<size_t>(e) + 1], -block);
      gradient.segment<3>(3 * b) += r * j;
      gradient.segment<3>(3 * a) -= r * j;
    }
    tbb::parallel_for(0, hinge_count, [&](int index) {
      const Hinge& h = patch_.hinges[static_cast<size_t>(index)];
      gradients[static_cast<size_t>(index)] = hinge_angle_gradient(h, x);
      residuals[static_cast<size_t>(index)] = wrap_angle(hinge_angle(h, x) - angles(index));
    });
    for (int index = 0; index < hinge_count; ++index) {
      const Hinge& h = patch_.hinges[static_cast<size_t>(index)];
      const Eigen::Matrix<double, 4, 3>& g = gradients[static_cast<size_t>(index)];
      const double r = residuals[static_cast<size_t>(index)];
      const int corners[4] = {h.a, h.b, h.c, h.d};
      const BlockSparseMatrix3::Slot* slots = &hinge_slots_[16 * static_cast<size_t>(index)];
      for (int i = 0; i < 4; ++i) {
        gradient.segment<3>(3 * corners[i]) += mu * r * g.row(i).transpose();
        for (int k = 0; k < 4; ++k) normal_matrix_.add(slots[4 * i + k], mu * g.row(i).transpose() * g.row(k));
      }
    }
    const double damping = kRegularization * std::max(normal_matrix_.mean_diagonal(), 1e-300);
    for (int v = 0; v < vertex_count; ++v) normal_matrix_.add_diagonal(v, damping);
    if (!normal_solver_.factorize(normal_matrix_.matrix())) break;
    const Eigen::VectorXd step = -normal_solver_.solve(gradient);
    if (!step.allFinite()) break;
    // Backtracking: the full Gauss-Newton step first, halved until the energy goes down.
    double scale = 1.0;
    bool accepted = false;
    Eigen::MatrixX3d trial(vertex_count, 3);
    double trial_energy = current;
    for (int attempt = 0; attempt < kLineSearchSteps; ++attempt, scale *= 0.5) {
      for (int v = 0; v < vertex_count; ++v) trial.row(v) = x.row(v) + scale * step.segment<3>(3 * v).transpose();
      trial_energy = energy(trial, lengths, angles, mu);
      if (trial_energy < current) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    x = trial;
    ++stats.iterations;
    const double decrease = current - trial_energy;
    current = trial_energy;
    if (decrease < options.tolerance * (current + decrease)) break;
  }
  stats.final_energy = current;
  return stats;
}

Eigen::MatrixX3d EdgeSpaceReconstruction::reconstruct(const Eigen::VectorXd& weights, const Eigen::VectorXd& lengths,
                                                      const Eigen::VectorXd& angles, const ReconstructionOptions& options,
                                                      ReconstructionStats* stats) {
  Eigen::MatrixX3d x = gradient_guess(weights);
  const ReconstructionStats result = refine(x, lengths, angles, options);
  if (stats != nullptr) *stats = result;
  return x;
}

}  // namespace posekit::interpolation
