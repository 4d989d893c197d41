// Example-based deformation by fast blended transformations: a pose X = D T spanned by an
// example-based dictionary D (see blend_dictionary.hpp), found from a few linear constraints by
// minimizing constraints + smoothness + as-rigid-as-possible energy against the examples, with
// rotation clusters and a global scale, by local/global iterations on a prefactorized system.
//
// Energy, in a frame where the first example (the reference) is centred and has unit area:
//   E(T, R, s) = alpha_c sum_r w_r |c_r^T D T - p_r|^2 + alpha_s tr(T^T Lambda T) + eps |T|^2
//              + sum_k omega_k sum_clusters sum_edges c_ij |(D T)_i - (D T)_j - s_k R_kc (x^k_i - x^k_j)|^2
// with omega_k = 1/K (average ARAP) or omega = one-hot on the best example (minimal ARAP). The quadratic
// part in T is the same in both, so one matrix, factorized once per constraint set, serves every step.
// The ARAP terms are projected into the reduced space in advance: an iteration costs
// O(atoms * clusters * examples) and never touches the vertices.
#pragma once

#include <posekit/blend_dictionary.hpp>
#include <posekit/mesh.hpp>
#include <posekit/skinning_decomposition.hpp>

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace posekit {

/// The dictionary a deformation ends in: the Laplace-Beltrami one; the skeleton one, whose weights a
/// skinning decomposition learns from the examples (the deformation starts in the Laplace-Beltrami
/// dictionary and changes to the skeleton one, as the paper does for articulated shapes); or, by
/// measurement, the one that rebuilds examples held out of the others better (see
/// BlendOptions::trial_examples).
enum class DictionaryChoice { lbo, skeleton, automatic };

/// "lbo", "skeleton" or "auto".
const char* dictionary_choice_name(DictionaryChoice choice);

/// Settings of BlendedDeformer; lengths and weights refer to the unit-area frame of the reference.
struct BlendOptions {
  /// Which dictionary (see DictionaryChoice); ignored with skinning weights given to the constructor.
  DictionaryChoice dictionary = DictionaryChoice::lbo;
  /// The skinning decomposition behind the skeleton dictionary.
  SkinningOptions skinning;
  /// automatic: up to this many examples (those farthest from the reference; never the reference) are
  /// each rebuilt from `trial_points` spread vertices by both dictionaries made from the other
  /// examples; the skeleton dictionary is chosen when its mean 95th-percentile vertex error is lower.
  /// Needs at least three examples (with fewer, the Laplace-Beltrami dictionary). >= 1 each.
  int trial_examples = 2;
  int trial_points = 20;
  /// Iterations in the skeleton dictionary after the change (average, then minimal ARAP; >= 0); the
  /// counts below apply to the Laplace-Beltrami dictionary before it.
  int skeleton_average_iterations = 0;
  int skeleton_minimal_iterations = 1;
  /// The skeleton dictionary holds the Laplace-Beltrami eigenfunctions beside the bone weights (true),
  /// or the bone weights alone, as in the paper (false).
  bool skeleton_keeps_eigenfunctions = true;
  /// m: Laplace-Beltrami eigenfunctions used as weights (>= 1; ignored when skinning weights are
  /// given).
  int eigenfunctions = 20;
  /// Fraction of the 4mK dictionary atoms kept by k-medoids (1 keeps them all); never fewer than
  /// 4m, and the reference's atoms of a constant weight function (if any) are always kept. In (0, 1].
  double atom_fraction = 0.5;
  /// Rotation clusters (k-means on motion across the examples; with skinning weights 0 means one per
  /// weight, by largest weight). >= 0.
  int rotation_clusters = 40;
  /// Weight of position (unit-area frame) against rotation (radians) in the cluster features
  /// (rotation_clusters(); >= 0).
  double cluster_position_weight = 1.0;
  /// alpha_c: weight of each linear constraint's squared distance against the ARAP energy (> 0).
  double constraint_weight = 1e3;
  /// alpha_s: weight of the smoothness of the blended maps (>= 0).
  double smoothness_weight = 1e-3;
  /// eps, relative to the mean diagonal of the ARAP matrix: picks the least-norm maps among equivalent
  /// ones (the dictionary's atoms are linearly dependent). > 0.
  double ridge = 1e-8;
  /// Elastic-net sparsity of the initial solve: the L1 weight as a fraction of the smallest weight that
  /// makes every map zero, in [0, 1). 0 turns the L1 term off (one solve with the initial
  /// factorization).
  double sparsity = 0.0;
  /// Local/global iterations with the average ARAP energy, then with the minimal ARAP energy (>= 0).
  int average_iterations = 4;
  int minimal_iterations = 4;
  /// Minimal ARAP picks its example by the energy after that example's global step (one forward
  /// substitution per example and iteration) instead of the energy at the current maps.
  bool example_choice_after_solve = false;
  /// A stage stops early when an iteration lowers the energy by less than this fraction of it (>= 0).
  double tolerance = 1e-5;
  /// Estimate the global scale s (closed form); false keeps s = 1.
  bool estimate_scale = true;
};

/// A linear constraint: sum_i coefficients[i] * x_{vertices[i]} should equal its target position; a
/// vertex position is one vertex with coefficient 1. `weight` multiplies alpha_c for this constraint.
struct LinearConstraint {
  std::vector<int> vertices;
  std::vector<double> coefficients;
  double weight = 1.0;
  /// The position constraint of one vertex.
  static LinearConstraint vertex(int index, double weight = 1.0) { return {{index}, {1.0}, weight}; }
};

/// What the precomputation did and what it cost.
struct BlendSetupReport {
  int vertices = 0;
  int examples = 0;
  int weights = 0;
  int full_atoms = 0;  ///< 4mK
  int atoms = 0;       ///< after reduction
  int clusters = 0;
  double reference_area = 0.0;  ///< surface area of the reference, in the examples' units
  /// The dictionary deformations end in ("lbo", "skeleton" or "weights" for given skinning weights);
  /// weights, atoms and clusters above are that dictionary's.
  std::string dictionary = "lbo";
  /// With a skinning decomposition (skeleton or automatic): its bones and RMS error over the examples
  /// (fraction of the diagonal); 0 otherwise.
  int bones = 0;
  double skinning_error = 0.0;
  /// automatic: the examples held out and each dictionary's mean 95th-percentile vertex error on them
  /// (fraction of the diagonal); 0 when no trial ran.
  struct {
    int examples = 0;
    double lbo = 0.0, skeleton = 0.0;
  } trial;
  struct {
    double weights = 0, dictionary = 0, clusters = 0, system = 0, skinning = 0, trial = 0, total = 0;
  } seconds;
};

/// One step of a deformation: its stage ("initial", "average", "minimal"), the energy after it,
/// the scale and, for minimal steps, the chosen example.
struct BlendIteration {
  std::string stage;
  double energy = 0.0;
  double scale = 1.0;
  int example = -1;
};

/// A deformation and everything needed to continue or interpolate it.
struct BlendResult {
  Eigen::MatrixX3d vertices;         ///< #V by 3, in the frame of the constraint targets
  Eigen::MatrixX3d targets;          ///< the constraint targets it was made for (#constraints by 3)
  Eigen::MatrixX3d transformations;  ///< #atoms by 3 (internal frame)
  /// Rotations of the last local step, index k * clusters + c, for every example k.
  std::vector<Eigen::Matrix3d> rotations;
  Eigen::VectorXd example_weights;   ///< omega_k of the last global step (1/K each, or one-hot)
  Eigen::VectorXd example_scales;    ///< s_k of the last global step
  double scale = 1.0;                ///< the estimated scale of the result against the examples
  int closest_example = -1;          ///< the example of the minimal ARAP energy, -1 if that stage did not run
  double energy = 0.0;               ///< final energy
  std::vector<BlendIteration> iterations;
  double seconds = 0.0;              ///< time of this deformation
};

/// Deforms a shape given by example poses from linear constraints. Precomputes weights, dictionary,
/// clusters and the projected ARAP terms once; set_constraints() factorizes the global matrix for one
/// constraint set, which add/remove/replace then update by rank-one updates and downdates of the
/// Cholesky factors instead of refactorizing. deform() is const and may run in several threads.
class BlendedDeformer {
 public:
  /// `examples`: K >= 1 poses of one connectivity; the first is the reference (weights, clusters,
  /// the internal frame). Laplace-Beltrami eigenfunctions of the reference are the weights. Throws
  /// ArgumentError for an empty set, a degenerate reference or options out of range.
  explicit BlendedDeformer(const PoseSet& examples, const BlendOptions& options = {});
  /// The same with #V by m skinning weights instead of eigenfunctions (rows need not sum to 1): the
  /// only dictionary (options.dictionary must be lbo).
  BlendedDeformer(const PoseSet& examples, const Eigen::MatrixXd& skinning_weights, const BlendOptions& options = {});
  /// The same as the first, with a skinning decomposition of these examples computed before (a cache)
  /// instead of a new one when options.dictionary is skeleton or automatic. Throws ArgumentError when
  /// it does not belong to these examples (vertex or example count).
  BlendedDeformer(const PoseSet& examples, const SkinningDecomposition& skinning, const BlendOptions& options);
  ~BlendedDeformer();
  BlendedDeformer(BlendedDeformer&&) noexcept;
  BlendedDeformer& operator=(BlendedDeformer&&) noexcept;

  const BlendOptions& options() const;
  const BlendSetupReport& setup_report() const;
  const BlendDictionary& dictionary() const;
  const Eigen::MatrixX3i& faces() const;
  int vertex_count() const;
  int example_count() const;
  int cluster_count() const;
  /// Per-vertex rotation cluster labels (of the dictionary deformations end in).
  const std::vector<int>& clusters() const;
  /// The skinning decomposition behind the skeleton dictionary (null without one).
  const SkinningDecomposition* skinning() const;

  /// Replaces the constraints and factorizes the two matrices (initial and global) anew. Throws
  /// ArgumentError for an empty list, a vertex out of range, mismatched sizes, or a non-finite or
  /// non-positive weight.
  void set_constraints(const std::vector<LinearConstraint>& constraints);
  /// Appends one constraint (rank-one update of both factorizations).
  void add_constraint(const LinearConstraint& constraint);
  /// Removes constraint `index` (rank-one downdate); later constraints move down by one.
  void remove_constraint(int index);
  /// Replaces constraint `index` (one downdate and one update).
  void replace_constraint(int index, const LinearConstraint& constraint);
  int constraint_count() const;
  const std::vector<LinearConstraint>& constraints() const;

  /// Deforms from the constraint targets (#constraints by 3, one row per constraint, in any frame and
  /// scale): the initial solve without rotations, then average-ARAP and minimal-ARAP iterations; with
  /// the skeleton dictionary, then the change to it and its own iterations (stages "skeleton ...").
  /// Throws ArgumentError when the sizes disagree, a target is not finite, or there are no constraints.
  BlendResult deform(const Eigen::Ref<const Eigen::MatrixX3d>& targets) const;
  /// The same, continuing from the transformations of `start` (a result of this deformer) instead of
  /// the initial solve, in the dictionary `start` ended in: for non-rigid ICP, where the constraints
  /// change a little between calls. `average_iterations` and
  /// `minimal_iterations` replace the options' counts when they are >= 0.
  BlendResult deform(const Eigen::Ref<const Eigen::MatrixX3d>& targets, const BlendResult& start,
                     int average_iterations = -1,
                     int minimal_iterations = -1) const;

  /// The pose at t in [0, 1] between two deformations of this deformer: rotations interpolated
  /// spherically (per example and cluster), scales and example weights linearly, then one global step
  /// of the ARAP energy alone; what the constraints added to each end is blended linearly, so t = 0 and
  /// t = 1 give a and b exactly. #V by 3. Throws ArgumentError for t outside [0, 1] or results of
  /// another deformer.
  Eigen::MatrixX3d interpolate(const BlendResult& a, const BlendResult& b, double t) const;

  /// #V by 3 vertices of the transformations (#atoms by 3, internal frame), in the targets' frame.
  Eigen::MatrixX3d vertices(const Eigen::Ref<const Eigen::MatrixX3d>& transformations) const;

 private:
  struct State;
  BlendedDeformer();
  /// `clusters` (optional, per vertex): rotation cluster labels that replace the options' choice.
  void build(const PoseSet& examples, const Eigen::MatrixXd* skinning_weights, const SkinningDecomposition* skinning,
             const std::vector<int>* clusters, const BlendOptions& options);
  /// deform() and its continuation in this deformer's own (first) dictionary; without `vertices` the
  /// result's vertices are left empty (the dictionary change needs only the transformations).
  BlendResult deform_in_own_dictionary(const Eigen::Ref<const Eigen::MatrixX3d>& targets, bool vertices = true) const;
  BlendResult continue_in_own_dictionary(const Eigen::Ref<const Eigen::MatrixX3d>& targets, const BlendResult& start,
                                         int average_iterations, int minimal_iterations, bool vertices = true) const;
  Eigen::MatrixX3d own_vertices(const Eigen::Ref<const Eigen::MatrixX3d>& transformations) const;
  /// DictionaryChoice::automatic: whether the skeleton dictionary rebuilds held-out examples better;
  /// fills report.trial.
  static bool skeleton_rebuilds_better(const PoseSet& examples, const BlendOptions& options, BlendSetupReport& report);
  std::unique_ptr<State> state_;
};

}  // namespace posekit
