// BlendedDeformer: the precomputation (weights, dictionary, clusters, projected ARAP terms).
#include <posekit/error.hpp>
#include <posekit/laplace_beltrami.hpp>
#include <posekit/rotation_clusters.hpp>

#include "blend/deformer_state.hpp"
#include "blend/rotation_fit.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace posekit {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void check_options(const BlendOptions& o) {
  const auto fail = [](const std::string& what) { throw ArgumentError("blend options: " + what); };
  if (o.eigenfunctions < 1) fail("eigenfunctions must be >= 1");
  if (!(o.atom_fraction > 0.0 && o.atom_fraction <= 1.0)) fail("atom_fraction must lie in (0, 1]");
  if (o.rotation_clusters < 0) fail("rotation_clusters must be >= 0");
  if (!(o.cluster_position_weight >= 0.0) || !std::isfinite(o.cluster_position_weight)) {
    fail("cluster_position_weight must be finite and >= 0");
  }
  if (!(o.constraint_weight > 0.0) || !std::isfinite(o.constraint_weight)) fail("constraint_weight must be finite and > 0");
  if (!(o.smoothness_weight >= 0.0) || !std::isfinite(o.smoothness_weight)) fail("smoothness_weight must be finite and >= 0");
  if (!(o.ridge > 0.0) || !std::isfinite(o.ridge)) fail("ridge must be finite and > 0");
  if (!(o.sparsity >= 0.0 && o.sparsity < 1.0)) fail("sparsity must lie in [0, 1)");
  if (o.average_iterations < 0 || o.minimal_iterations < 0) fail("iteration counts must be >= 0");
  if (!(o.tolerance >= 0.0) || !std::isfinite(o.tolerance)) fail("tolerance must be finite and >= 0");
  if (o.trial_examples < 1 || o.trial_points < 1) fail("trial_examples and trial_points must be >= 1");
  if (o.skeleton_average_iterations < 0 || o.skeleton_minimal_iterations < 0) fail("iteration counts must be >= 0");
}

// Rotation and translation (mass-weighted Kabsch) that carry `moving` onto `fixed`.
Eigen::MatrixX3d rigidly_aligned(const Eigen::Ref<const Eigen::MatrixX3d>& moving,
                                 const Eigen::Ref<const Eigen::MatrixX3d>& fixed, const Eigen::VectorXd& mass) {
  const double total = mass.sum();
  const Eigen::RowVector3d moving_center = (mass.transpose() * moving) / total;
  const Eigen::RowVector3d fixed_center = (mass.transpose() * fixed) / total;
  const Eigen::MatrixX3d a = moving.rowwise() - moving_center;
  const Eigen::MatrixX3d b = fixed.rowwise() - fixed_center;
  const Eigen::Matrix3d covariance = b.transpose() * mass.asDiagonal() * a;  // sum m b a^T
  const Eigen::Matrix3d rotation = detail::closest_rotation(covariance);    // b ~ R a
  return (a * rotation.transpose()).rowwise() + fixed_center;
}

// The ARAP energy sums c_e |y_e - s R e_e|^2 with a different rotation per cluster, which is not a
// gradient field, so a negative cotangent weight (an obtuse triangle) could make it negative: the
// ARAP terms use the cotangent weights clamped at zero.
Eigen::SparseMatrix<double> arap_laplacian(const Eigen::SparseMatrix<double>& cotangent) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(cotangent.nonZeros()));
  for (int col = 0; col < cotangent.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(cotangent, col); it; ++it) {
      const int row = static_cast<int>(it.row());
      if (row == col) continue;
      const double weight = std::max(-it.value(), 0.0);
      if (weight == 0.0) continue;
      entries.emplace_back(row, col, -weight);
      entries.emplace_back(col, col, weight);
    }
  }
  Eigen::SparseMatrix<double> laplacian(cotangent.rows(), cotangent.cols());
  laplacian.setFromTriplets(entries.begin(), entries.end());
  return laplacian;
}

// D^T L D by column blocks in parallel: the most expensive product of the precomputation.
Eigen::MatrixXd arap_matrix(const Eigen::SparseMatrix<double>& laplacian, const Eigen::MatrixXd& d) {
  const Eigen::MatrixXd ld = laplacian * d;
  const int n = static_cast<int>(d.cols());
  Eigen::MatrixXd h(n, n);
  const int block = 32;
  tbb::parallel_for(0, (n + block - 1) / block, [&](int b) {
    const int first = b * block;
    const int width = std::min(block, n - first);
    h.middleCols(first, width).noalias() = d.transpose() * ld.middleCols(first, width);
  });
  return 0.5 * (h + h.transpose());
}

}  // namespace

const char* dictionary_choice_name(DictionaryChoice choice) {
  switch (choice) {
    case DictionaryChoice::skeleton:
      return "skeleton";
    case DictionaryChoice::automatic:
      return "auto";
    case DictionaryChoice::lbo:
      break;
  }
  return "lbo";
}

void BlendedDeformer::build(const PoseSet& examples, const Eigen::MatrixXd* skinning_weights,
                            const SkinningDecomposition* skinning, const std::vector<int>* clusters,
                            const BlendOptions& options) {
  const Clock::time_point start = Clock::now();
  State& s = *state_;
  check_options(options);
  if (examples.pose_count() < 1) throw ArgumentError("blended deformation needs at least one example pose");
  if (skinning_weights != nullptr && options.dictionary != DictionaryChoice::lbo) {
    throw ArgumentError("blend options: skinning weights are the dictionary; the " +
                        std::string(dictionary_choice_name(options.dictionary)) + " dictionary cannot be chosen with them");
  }
  if (skinning != nullptr && (skinning->vertex_count() != examples.vertex_count() ||
                              skinning->example_count() != examples.pose_count())) {
    throw ArgumentError("the skinning decomposition has " + std::to_string(skinning->vertex_count()) + " vertices and " +
                        std::to_string(skinning->example_count()) + " examples for " +
                        std::to_string(examples.vertex_count()) + " vertices and " +
                        std::to_string(examples.pose_count()) + " examples");
  }
  s.options = options;
  s.faces = examples.faces();
  const int vertex_count = examples.vertex_count();
  const int example_count = examples.pose_count();
  try {
    check_laplace_beltrami_mesh(examples.pose(0), s.faces);
  } catch (const ArgumentError& error) {
    throw ArgumentError("the reference pose (the first example) cannot carry blending weights: " +
                        std::string(error.what()));
  }
  for (int k = 1; k < example_count; ++k) {
    if (!examples.pose(k).allFinite()) throw ArgumentError("example " + std::to_string(k) + " has a non-finite coordinate");
  }

  // Internal frame: the reference centred at its mass centroid, with unit area.
  const Eigen::VectorXd raw_mass = lumped_mass(examples.pose(0), s.faces);
  const double area = raw_mass.sum();
  s.center = (raw_mass.transpose() * examples.pose(0)) / area;
  s.scale = 1.0 / std::sqrt(area);
  std::vector<Eigen::MatrixX3d> poses;
  poses.reserve(static_cast<size_t>(example_count));
  poses.push_back((examples.pose(0).rowwise() - s.center) * s.scale);
  const Eigen::VectorXd mass = lumped_mass(poses.front(), s.faces);
  for (int k = 1; k < example_count; ++k) {
    poses.push_back(rigidly_aligned((examples.pose(k).rowwise() - s.center) * s.scale, poses.front(), mass));
  }
  const Eigen::SparseMatrix<double> laplacian = cotangent_laplacian(poses.front(), s.faces);

  // Weights and their smoothness.
  Clock::time_point stage = Clock::now();
  Eigen::MatrixXd weights;
  if (skinning_weights != nullptr) {
    if (skinning_weights->rows() != vertex_count || skinning_weights->cols() < 1) {
      throw ArgumentError("the skinning weights have " + std::to_string(skinning_weights->rows()) + " rows for " +
                          std::to_string(vertex_count) + " vertices");
    }
    if (!skinning_weights->allFinite()) throw ArgumentError("the skinning weights have a non-finite value");
    weights = *skinning_weights;
  } else {
    if (options.eigenfunctions >= vertex_count) {
      throw ArgumentError("blend options: " + std::to_string(options.eigenfunctions) +
                          " eigenfunctions requested for a mesh of " + std::to_string(vertex_count) + " vertices");
    }
    weights = laplace_beltrami_basis(poses.front(), s.faces, options.eigenfunctions).eigenfunctions;
  }
  const Eigen::MatrixXd weight_smooth = weight_smoothness(laplacian, mass, weights);
  s.report.seconds.weights = seconds_since(stage);

  // Dictionary, reduced by k-medoids.
  stage = Clock::now();
  // The reduction removes what the examples repeat; it keeps at least one example's worth of atoms
  // (4m), and always the four of the reference with a constant weight, so that any affine map of the
  // reference stays in the space. A local weight (one that vanishes on part of the mesh, as a bone's
  // does) keeps the reference's four atoms too: its atoms say nothing of the other weights', so
  // k-medoids would drop some bones' atoms altogether (measured in docs/deform-register.md, "What the
  // skeleton dictionary holds").
  const BlendDictionary full(poses, weights);
  const int per_example = 4 * full.weight_count();
  const int kept = std::max(std::min(per_example, full.atom_count()),
                            static_cast<int>(std::lround(options.atom_fraction * full.atom_count())));
  std::vector<int> keep;
  for (int j = 0; j < full.weight_count(); ++j) {
    const Eigen::Index zeros = (weights.col(j).array() == 0.0).count();
    if (zeros * 100 >= vertex_count) {
      for (int a = 0; a < 4; ++a) keep.push_back(4 * j + a);  // example 0 comes first in the full dictionary
    }
  }
  for (int j = 0; j < full.weight_count(); ++j) {
    const double first = weights(0, j);
    if (first != 0.0 && (weights.col(j).array() - first).abs().maxCoeff() <= 1e-9 * std::abs(first)) {
      for (int a = 0; a < 4; ++a) keep.push_back(4 * j + a);  // example 0 comes first in the full dictionary
      break;
    }
  }
  s.dictionary = reduce_dictionary(full, kept, mass, keep);
  const Eigen::MatrixXd d = s.dictionary.matrix();
  s.product = detail::DictionaryProduct(s.dictionary);
  s.report.seconds.dictionary = seconds_since(stage);

  // Rotation clusters.
  stage = Clock::now();
  if (clusters != nullptr) {
    s.clusters = *clusters;
  } else if (skinning_weights != nullptr && options.rotation_clusters == 0) {
    s.clusters = weight_clusters(weights);
  } else {
    const int count = std::min(vertex_count, std::max(1, options.rotation_clusters));
    s.clusters = rotation_clusters(poses, s.faces, count, options.cluster_position_weight);
  }
  s.cluster_count = 1 + *std::max_element(s.clusters.begin(), s.clusters.end());
  s.report.seconds.clusters = seconds_since(stage);

  // Projected ARAP terms: D^T L D and, per example and cluster, G_kc = D^T F_kc with
  // F_kc = sum over the cluster's half edges of c_e (delta_i - delta_j) e_k^T.
  stage = Clock::now();
  const int n_atoms = s.atom_count();
  const int nc = s.cluster_count;
  const Eigen::SparseMatrix<double> arap = arap_laplacian(laplacian);
  const Eigen::MatrixXd h = arap_matrix(arap, d);
  s.projected.resize(n_atoms, 3 * nc * example_count);
  s.example_energy = Eigen::VectorXd::Zero(example_count);
  for (int k = 0; k < example_count; ++k) {
    const Eigen::MatrixX3d& x = poses[static_cast<size_t>(k)];
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<size_t>(arap.nonZeros()) * 6);
    for (int col = 0; col < arap.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(arap, col); it; ++it) {
        const int i = static_cast<int>(it.row());
        const int j = col;
        if (i <= j) continue;  // each undirected edge once
        const double weight = -it.value();
        const Eigen::RowVector3d e = x.row(i) - x.row(j);
        s.example_energy(k) += weight * e.squaredNorm();
        for (int endpoint : {i, j}) {
          const int column = 3 * s.clusters[static_cast<size_t>(endpoint)];
          for (int b = 0; b < 3; ++b) {
            entries.emplace_back(i, column + b, 0.5 * weight * e(b));
            entries.emplace_back(j, column + b, -0.5 * weight * e(b));
          }
        }
      }
    }
    Eigen::SparseMatrix<double> f(vertex_count, 3 * nc);
    f.setFromTriplets(entries.begin(), entries.end());
    const Eigen::SparseMatrix<double> ft = f.transpose();
    s.projected.middleCols(3 * nc * k, 3 * nc) = (ft * d).transpose();
  }
  const Eigen::MatrixXd lambda = s.dictionary.transformation_smoothness(weight_smooth);
  const double eps = options.ridge * std::max(h.diagonal().mean(), 1e-300);
  s.base_initial = options.smoothness_weight * lambda;
  s.base_initial.diagonal().array() += eps;
  s.base_global = s.base_initial + h;
  s.unconstrained.compute(s.base_global);
  if (s.unconstrained.info() != Eigen::Success) {
    throw ArgumentError("blended deformation: the ARAP matrix of the dictionary is not positive definite");
  }
  s.report.seconds.system = seconds_since(stage);

  s.report.vertices = vertex_count;
  s.report.examples = example_count;
  s.report.weights = static_cast<int>(weights.cols());
  s.report.full_atoms = full.atom_count();
  s.report.atoms = n_atoms;
  s.report.clusters = nc;
  s.report.reference_area = area;
  s.report.dictionary = skinning_weights != nullptr ? "weights" : "lbo";

  bool use_skeleton = options.dictionary == DictionaryChoice::skeleton;
  if (options.dictionary == DictionaryChoice::automatic) {
    stage = Clock::now();
    use_skeleton = skeleton_rebuilds_better(examples, options, s.report);
    s.report.seconds.trial = seconds_since(stage);
  }
  if (options.dictionary != DictionaryChoice::lbo) {
    stage = Clock::now();
    if (use_skeleton || skinning != nullptr) {
      s.skinning = std::make_unique<SkinningDecomposition>(skinning != nullptr ? *skinning
                                                                               : decompose_skinning(examples, options.skinning));
      s.report.bones = s.skinning->bone_count();
      s.report.skinning_error = s.skinning->rms_error;
    }
    s.report.seconds.skinning = seconds_since(stage);
    if (use_skeleton) {
      BlendOptions richer = options;
      richer.dictionary = DictionaryChoice::lbo;
      richer.average_iterations = options.skeleton_average_iterations;
      richer.minimal_iterations = options.skeleton_minimal_iterations;
      Eigen::MatrixXd richer_weights = s.skinning->weights;
      if (options.skeleton_keeps_eigenfunctions) {
        richer_weights.resize(vertex_count, weights.cols() + s.skinning->weights.cols());
        richer_weights << weights, s.skinning->weights;
      }
      const std::vector<int> bone_clusters = weight_clusters(s.skinning->weights);  // one per bone
      s.richer.reset(new BlendedDeformer());
      s.richer->build(examples, &richer_weights, nullptr, &bone_clusters, richer);
      s.change = std::make_unique<DictionaryChange>(s.dictionary, s.richer->dictionary(), mass);
      const BlendSetupReport& r = s.richer->setup_report();
      s.report.dictionary = "skeleton";
      s.report.weights = r.weights;
      s.report.full_atoms = r.full_atoms;
      s.report.atoms = r.atoms;
      s.report.clusters = r.clusters;
      s.report.seconds.weights += r.seconds.weights;
      s.report.seconds.dictionary += r.seconds.dictionary;
      s.report.seconds.clusters += r.seconds.clusters;
      s.report.seconds.system += r.seconds.system;
    }
  }
  s.report.seconds.total = seconds_since(start);
}

BlendedDeformer::BlendedDeformer(const PoseSet& examples, const BlendOptions& options) : state_(std::make_unique<State>()) {
  build(examples, nullptr, nullptr, nullptr, options);
}

BlendedDeformer::BlendedDeformer(const PoseSet& examples, const SkinningDecomposition& skinning,
                                 const BlendOptions& options)
    : state_(std::make_unique<State>()) {
  build(examples, nullptr, &skinning, nullptr, options);
}

BlendedDeformer::BlendedDeformer(const PoseSet& examples, const Eigen::MatrixXd& skinning_weights,
                                 const BlendOptions& options)
    : state_(std::make_unique<State>()) {
  build(examples, &skinning_weights, nullptr, nullptr, options);
}

BlendedDeformer::BlendedDeformer() : state_(std::make_unique<State>()) {}
BlendedDeformer::~BlendedDeformer() = default;
BlendedDeformer::BlendedDeformer(BlendedDeformer&&) noexcept = default;
BlendedDeformer& BlendedDeformer::operator=(BlendedDeformer&&) noexcept = default;

const BlendOptions& BlendedDeformer::options() const { return state_->options; }
const BlendSetupReport& BlendedDeformer::setup_report() const { return state_->report; }
const BlendDictionary& BlendedDeformer::dictionary() const {
  return state_->richer ? state_->richer->dictionary() : state_->dictionary;
}
const Eigen::MatrixX3i& BlendedDeformer::faces() const { return state_->faces; }
int BlendedDeformer::vertex_count() const { return state_->dictionary.vertex_count(); }
int BlendedDeformer::example_count() const { return state_->example_count(); }
int BlendedDeformer::cluster_count() const {
  return state_->richer ? state_->richer->cluster_count() : state_->cluster_count;
}
const std::vector<int>& BlendedDeformer::clusters() const {
  return state_->richer ? state_->richer->clusters() : state_->clusters;
}
const SkinningDecomposition* BlendedDeformer::skinning() const { return state_->skinning.get(); }

Eigen::MatrixX3d BlendedDeformer::vertices(const Eigen::Ref<const Eigen::MatrixX3d>& transformations) const {
  if (state_->richer) return state_->richer->vertices(transformations);
  return own_vertices(transformations);
}

Eigen::MatrixX3d BlendedDeformer::own_vertices(const Eigen::Ref<const Eigen::MatrixX3d>& transformations) const {
  const State& s = *state_;
  if (transformations.rows() != s.atom_count()) {
    throw ArgumentError("BlendedDeformer::vertices: " + std::to_string(transformations.rows()) +
                        " transformation rows for " + std::to_string(s.atom_count()) + " atoms");
  }
  return (s.product(transformations) / s.scale).rowwise() + s.center;
}

}  // namespace posekit
