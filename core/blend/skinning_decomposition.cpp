// Smooth skinning decomposition with rigid bones, a skeleton, and the refinement on the skeleton.
//
// 1. Rigid parts: bones are added one at a time, each seeded on the vertices the others fit worst,
//    followed by k-means sweeps in which every vertex joins the bone whose motions fit it best.
// 2. Alternation (Le and Deng): per vertex, the non-negative weights over the bones found near it that
//    sum to one, fit the examples and stay close to the neighbours' weights (at most `influences`
//    nonzero); per bone and example, the weighted Procrustes motion that fits what the other bones
//    leave over.
// 3. Skeleton (bone_skeleton.hpp), then the same alternation with each bone's joint held to its
//    parent's motion and each vertex blending only its own bone and the bones jointed to it.
#include <posekit/error.hpp>
#include <posekit/geometry.hpp>
#include <posekit/laplace_beltrami.hpp>
#include <posekit/skinning_decomposition.hpp>
#include <posekit/topology.hpp>

#include "blend/bone_skeleton.hpp"
#include "blend/nonnegative_least_squares.hpp"
#include "blend/rotation_fit.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace posekit {
namespace {

using detail::RigidMotion;

constexpr int kMaxInfluences = 8;

// The examples in an internal frame: the reference centred, its diagonal 1.
struct Problem {
  Eigen::RowVector3d center;
  double scale = 1.0;
  Eigen::MatrixX3d rest;
  std::vector<Eigen::MatrixX3d> poses;  // [0] is the rest pose
  Eigen::VectorXd mass;                 // lumped mass, mean 1
  AdjacencyLists neighbours;
  double edge_length = 0.0;
  int vertices = 0;
  int examples = 0;
};

// Sparse weights: up to kMaxInfluences (bone, weight) pairs per vertex, unused slots bone -1.
struct Weights {
  Eigen::Matrix<int, Eigen::Dynamic, kMaxInfluences, Eigen::RowMajor> bone;
  Eigen::Matrix<double, Eigen::Dynamic, kMaxInfluences, Eigen::RowMajor> weight;
  int primary(int i) const {
    int best = bone(i, 0);
    double largest = -1.0;
    for (int s = 0; s < kMaxInfluences && bone(i, s) >= 0; ++s) {
      if (weight(i, s) > largest) {
        largest = weight(i, s);
        best = bone(i, s);
      }
    }
    return best;
  }
};

// Sums of a weighted Procrustes problem: minimize sum |w (R p + t) - q|^2 over rotations R.
struct ProcrustesSums {
  double w2 = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d q = Eigen::Vector3d::Zero();
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  void add(const Eigen::Vector3d& point, const Eigen::Vector3d& target, double w) {
    w2 += w * w;
    p += w * w * point;
    q += w * target;
    s += w * target * point.transpose();
  }
  RigidMotion solve(const RigidMotion& fallback) const {
    if (!(w2 > 1e-300)) return fallback;
    const Eigen::Vector3d p_mean = p / w2;
    const Eigen::Vector3d q_mean = q / w2;
    const Eigen::Matrix3d r = detail::closest_rotation_svd(s - w2 * q_mean * p_mean.transpose());
    RigidMotion motion;
    motion.leftCols<3>() = r;
    motion.col(3) = q_mean - r * p_mean;
    return motion;
  }
};

Eigen::Vector3d apply(const RigidMotion& m, const Eigen::Vector3d& x) { return m.leftCols<3>() * x + m.col(3); }

void check_options(const SkinningOptions& o, int vertices) {
  const auto fail = [](const std::string& what) { throw ArgumentError("skinning decomposition: " + what); };
  if (o.bones < 0) fail("bones must be >= 0 (0 chooses the count)");
  if (o.bones > vertices) {
    fail(std::to_string(o.bones) + " bones requested for a mesh of " + std::to_string(vertices) + " vertices");
  }
  if (o.bones == 0 && o.max_bones < 1) fail("max_bones must be >= 1");
  if (!(o.fit_tolerance > 0.0) || !std::isfinite(o.fit_tolerance)) fail("fit_tolerance must be finite and > 0");
  if (o.influences < 1 || o.influences > kMaxInfluences) fail("influences must lie in [1, 8]");
  if (o.iterations < 0 || o.skeleton_iterations < 0) fail("iteration counts must be >= 0");
  if (!(o.smoothness >= 0.0) || !std::isfinite(o.smoothness)) fail("smoothness must be finite and >= 0");
  if (!(o.joint_weight >= 0.0) || !std::isfinite(o.joint_weight)) fail("joint_weight must be finite and >= 0");
}

Problem make_problem(const PoseSet& examples) {
  Problem problem;
  problem.vertices = examples.vertex_count();
  problem.examples = examples.pose_count();
  const Eigen::MatrixX3d& reference = examples.pose(0);
  try {
    check_laplace_beltrami_mesh(reference, examples.faces());
  } catch (const ArgumentError& error) {
    throw ArgumentError("skinning decomposition: the reference pose (the first example): " + std::string(error.what()));
  }
  for (int k = 1; k < problem.examples; ++k) {
    if (!examples.pose(k).allFinite()) {
      throw ArgumentError("skinning decomposition: example " + std::to_string(k) + " has a non-finite coordinate");
    }
  }
  const double diagonal = bounding_box_diagonal(reference);
  if (!(diagonal > 0.0)) throw ArgumentError("skinning decomposition: the reference pose has no extent");
  problem.center = reference.colwise().mean();
  problem.scale = 1.0 / diagonal;
  for (int k = 0; k < problem.examples; ++k) {
    problem.poses.push_back((examples.pose(k).rowwise() - problem.center) * problem.scale);
  }
  problem.rest = problem.poses.front();
  problem.mass = lumped_mass(problem.rest, examples.faces());
  problem.mass /= problem.mass.mean();
  problem.neighbours = vertex_neighbours(examples.faces(), problem.vertices);
  problem.edge_length = edge_lengths(problem.rest, edge_map(examples.faces()).edges).mean();
  return problem;
}

// ---- 1. Rigid parts ----------------------------------------------------------------------------

// Mass-weighted rigid motions of every labelled part to every example (k >= 1); motions[k * B + j].
std::vector<RigidMotion> fit_parts(const Problem& problem, const std::vector<int>& labels, int bones) {
  std::vector<RigidMotion> motions(static_cast<size_t>(problem.examples * bones), RigidMotion::Identity());
  tbb::parallel_for(1, problem.examples, [&](int k) {
    std::vector<ProcrustesSums> sums(static_cast<size_t>(bones));
    const Eigen::MatrixX3d& pose = problem.poses[static_cast<size_t>(k)];
    for (int i = 0; i < problem.vertices; ++i) {
      const double w = std::sqrt(problem.mass(i));
      sums[static_cast<size_t>(labels[static_cast<size_t>(i)])].add(problem.rest.row(i).transpose(),
                                                                     w * pose.row(i).transpose(), w);
    }
    for (int j = 0; j < bones; ++j) {
      motions[static_cast<size_t>(k * bones + j)] = sums[static_cast<size_t>(j)].solve(RigidMotion::Identity());
    }
  });
  return motions;
}

double part_error(const Problem& problem, const std::vector<RigidMotion>& motions, int bones, int bone, int i) {
  double error = 0.0;
  const Eigen::Vector3d p = problem.rest.row(i).transpose();
  for (int k = 1; k < problem.examples; ++k) {
    error += (apply(motions[static_cast<size_t>(k * bones + bone)], p) -
              problem.poses[static_cast<size_t>(k)].row(i).transpose())
                 .squaredNorm();
  }
  return error;
}

// Every vertex to the part that fits it best; `errors` receives its squared error summed over the
// examples. Returns the number of vertices that changed part.
int assign_parts(const Problem& problem, const std::vector<RigidMotion>& motions, int bones, std::vector<int>& labels,
                 Eigen::VectorXd& errors) {
  std::vector<int> changed(static_cast<size_t>(problem.vertices), 0);
  errors.resize(problem.vertices);
  tbb::parallel_for(0, problem.vertices, [&](int i) {
    int best = labels[static_cast<size_t>(i)];
    double lowest = part_error(problem, motions, bones, best, i);
    for (int j = 0; j < bones; ++j) {
      if (j == best) continue;
      const double e = part_error(problem, motions, bones, j, i);
      if (e < lowest) {
        lowest = e;
        best = j;
      }
    }
    changed[static_cast<size_t>(i)] = best != labels[static_cast<size_t>(i)];
    labels[static_cast<size_t>(i)] = best;
    errors(i) = lowest;
  });
  return std::accumulate(changed.begin(), changed.end(), 0);
}

// A new part on the vertex fitted worst and the rings around it, enough vertices to fix a motion.
void seed_part(const Problem& problem, const Eigen::VectorXd& errors, int size, int bone, std::vector<int>& labels) {
  Eigen::Index seed = 0;
  errors.maxCoeff(&seed);
  std::vector<char> seen(static_cast<size_t>(problem.vertices), 0);
  std::vector<int> front = {static_cast<int>(seed)};
  seen[static_cast<size_t>(seed)] = 1;
  int taken = 0;
  while (!front.empty() && taken < size) {
    std::vector<int> next;
    for (int v : front) {
      labels[static_cast<size_t>(v)] = bone;
      ++taken;
      for (int u : problem.neighbours[v]) {
        if (!seen[static_cast<size_t>(u)]) {
          seen[static_cast<size_t>(u)] = 1;
          next.push_back(u);
        }
      }
    }
    front.swap(next);
  }
}

double rms(const Problem& problem, const Eigen::VectorXd& squared_errors) {
  return std::sqrt(squared_errors.sum() / (static_cast<double>(problem.vertices) * std::max(1, problem.examples - 1)));
}

// Labels of the rigid parts; `bones` receives their number.
std::vector<int> rigid_parts(const Problem& problem, const SkinningOptions& options, int& bones) {
  const int target = options.bones > 0 ? options.bones : std::min(options.max_bones, problem.vertices);
  const int seed_size = std::max(12, problem.vertices / (4 * target));
  std::vector<int> labels(static_cast<size_t>(problem.vertices), 0);
  bones = 1;
  std::vector<RigidMotion> motions = fit_parts(problem, labels, bones);
  Eigen::VectorXd errors;
  assign_parts(problem, motions, bones, labels, errors);
  while (bones < target) {
    if (options.bones == 0 && rms(problem, errors) <= options.fit_tolerance) break;
    seed_part(problem, errors, seed_size, bones, labels);
    ++bones;
    for (int sweep = 0; sweep < 3; ++sweep) {
      motions = fit_parts(problem, labels, bones);
      if (assign_parts(problem, motions, bones, labels, errors) == 0) break;
    }
  }
  for (int sweep = 0; sweep < 10; ++sweep) {
    motions = fit_parts(problem, labels, bones);
    if (assign_parts(problem, motions, bones, labels, errors) == 0) break;
  }
  return labels;
}

// ---- 2. Alternation ------------------------------------------------------------------------------

struct Alternation {
  const Problem& problem;
  const SkinningOptions& options;
  int bones = 0;
  Weights weights;
  std::vector<RigidMotion> motions;  // [k * bones + j], k = 0 the identity
  const detail::BoneSkeleton* skeleton = nullptr;

  // Bones that may influence vertex i: the largest-weight bones of the vertices within two rings, and
  // on the skeleton only those jointed to the vertex's own bone.
  std::vector<int> candidates(int i, const std::vector<int>& primary) const {
    std::vector<int> bones_near = {primary[static_cast<size_t>(i)]};
    for (int u : problem.neighbours[i]) {
      bones_near.push_back(primary[static_cast<size_t>(u)]);
      for (int v : problem.neighbours[u]) bones_near.push_back(primary[static_cast<size_t>(v)]);
    }
    std::sort(bones_near.begin(), bones_near.end());
    bones_near.erase(std::unique(bones_near.begin(), bones_near.end()), bones_near.end());
    if (skeleton == nullptr) return bones_near;
    const int own = primary[static_cast<size_t>(i)];
    const std::vector<int>& jointed = skeleton->jointed[static_cast<size_t>(own)];
    std::vector<int> kept;
    for (int b : bones_near) {
      if (b == own || std::find(jointed.begin(), jointed.end(), b) != jointed.end()) kept.push_back(b);
    }
    return kept;
  }

  void update_weights() {
    const std::vector<int> primary = primaries();
    const Weights previous = weights;
    const int k_count = problem.examples;
    const double smooth = (k_count - 1) * options.smoothness * options.smoothness * problem.edge_length * problem.edge_length;
    tbb::parallel_for(0, problem.vertices, [&](int i) {
      const std::vector<int> near = candidates(i, primary);
      const int n = static_cast<int>(near.size());
      const auto slot_of = [&](int bone) {
        const auto it = std::lower_bound(near.begin(), near.end(), bone);
        return it != near.end() && *it == bone ? static_cast<int>(it - near.begin()) : -1;
      };
      Eigen::MatrixXd a(3 * (k_count - 1), n);
      Eigen::VectorXd b(3 * (k_count - 1));
      const Eigen::Vector3d p = problem.rest.row(i).transpose();
      for (int k = 1; k < k_count; ++k) {
        b.segment<3>(3 * (k - 1)) = problem.poses[static_cast<size_t>(k)].row(i).transpose();
        for (int c = 0; c < n; ++c) {
          a.block<3, 1>(3 * (k - 1), c) = apply(motions[static_cast<size_t>(k * bones + near[static_cast<size_t>(c)])], p);
        }
      }
      Eigen::VectorXd mean = Eigen::VectorXd::Zero(n);
      const IndexRange ring = problem.neighbours[i];
      for (int u : ring) {
        for (int s = 0; s < kMaxInfluences && previous.bone(u, s) >= 0; ++s) {
          const int c = slot_of(previous.bone(u, s));
          if (c >= 0) mean(c) += previous.weight(u, s);
        }
      }
      if (!ring.empty()) mean /= ring.size();
      Eigen::MatrixXd g = a.transpose() * a;
      const double sum_weight = 1e4 * (g.trace() / n + smooth) + 1e-12;
      g.diagonal().array() += smooth;
      g.array() += sum_weight;
      Eigen::VectorXd h = a.transpose() * b + smooth * mean;
      h.array() += sum_weight;
      Eigen::VectorXd w = detail::nonnegative_least_squares(g, h);
      std::vector<int> order(static_cast<size_t>(n));
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](int x, int y) { return w(x) > w(y); });
      int nonzero = static_cast<int>((w.array() > 0.0).count());
      if (nonzero > options.influences) {
        // Keep the largest and solve again on those alone.
        order.resize(static_cast<size_t>(options.influences));
        std::sort(order.begin(), order.end());
        Eigen::MatrixXd g_kept(options.influences, options.influences);
        Eigen::VectorXd h_kept(options.influences);
        for (int x = 0; x < options.influences; ++x) {
          h_kept(x) = h(order[static_cast<size_t>(x)]);
          for (int y = 0; y < options.influences; ++y) g_kept(x, y) = g(order[static_cast<size_t>(x)], order[static_cast<size_t>(y)]);
        }
        const Eigen::VectorXd kept = detail::nonnegative_least_squares(g_kept, h_kept);
        w.setZero();
        for (int x = 0; x < options.influences; ++x) w(order[static_cast<size_t>(x)]) = kept(x);
        nonzero = static_cast<int>((w.array() > 0.0).count());
      }
      weights.bone.row(i).setConstant(-1);
      weights.weight.row(i).setZero();
      const double total = w.sum();
      if (!(total > 0.0)) {
        weights.bone(i, 0) = primary[static_cast<size_t>(i)];
        weights.weight(i, 0) = 1.0;
        return;
      }
      int slot = 0;
      for (int c = 0; c < n; ++c) {
        if (w(c) > 0.0) {
          weights.bone(i, slot) = near[static_cast<size_t>(c)];
          weights.weight(i, slot) = w(c) / total;
          ++slot;
        }
      }
    });
  }

  void update_motions() {
    // Each bone's vertices with their weights.
    std::vector<std::vector<std::pair<int, double>>> members(static_cast<size_t>(bones));
    for (int i = 0; i < problem.vertices; ++i) {
      for (int s = 0; s < kMaxInfluences && weights.bone(i, s) >= 0; ++s) {
        members[static_cast<size_t>(weights.bone(i, s))].emplace_back(i, weights.weight(i, s));
      }
    }
    std::vector<double> joint_weight(static_cast<size_t>(bones), 0.0);
    if (skeleton != nullptr) {
      for (int j = 0; j < bones; ++j) {
        double total = 0.0;
        for (const auto& [i, w] : members[static_cast<size_t>(j)]) total += problem.mass(i) * w * w;
        joint_weight[static_cast<size_t>(j)] = options.joint_weight * total;
      }
    }
    tbb::parallel_for(1, problem.examples, [&](int k) {
      const Eigen::MatrixX3d& pose = problem.poses[static_cast<size_t>(k)];
      RigidMotion* motion = &motions[static_cast<size_t>(k * bones)];
      Eigen::MatrixX3d left_over = pose;  // the example less the skinned pose
      for (int i = 0; i < problem.vertices; ++i) {
        const Eigen::Vector3d p = problem.rest.row(i).transpose();
        for (int s = 0; s < kMaxInfluences && weights.bone(i, s) >= 0; ++s) {
          left_over.row(i) -= weights.weight(i, s) * apply(motion[weights.bone(i, s)], p).transpose();
        }
      }
      for (int j = 0; j < bones; ++j) {
        const RigidMotion before = motion[j];
        ProcrustesSums sums;
        for (const auto& [i, w] : members[static_cast<size_t>(j)]) {
          const Eigen::Vector3d p = problem.rest.row(i).transpose();
          const double root_mass = std::sqrt(problem.mass(i));
          const Eigen::Vector3d q = left_over.row(i).transpose() + w * apply(before, p);
          sums.add(p, root_mass * q, root_mass * w);
        }
        const int parent = skeleton != nullptr ? skeleton->parents[static_cast<size_t>(j)] : -1;
        if (parent >= 0 && joint_weight[static_cast<size_t>(j)] > 0.0) {
          const Eigen::Vector3d joint = skeleton->joints.row(j).transpose();
          const double w = std::sqrt(joint_weight[static_cast<size_t>(j)]);
          sums.add(joint, w * apply(motion[parent], joint), w);
        }
        const RigidMotion after = sums.solve(before);
        motion[j] = after;
        for (const auto& [i, w] : members[static_cast<size_t>(j)]) {
          const Eigen::Vector3d p = problem.rest.row(i).transpose();
          left_over.row(i) -= w * (apply(after, p) - apply(before, p)).transpose();
        }
      }
    });
  }

  // Per vertex, squared error summed over the examples; `largest` (if given) the largest distance.
  Eigen::VectorXd errors(Eigen::VectorXd* largest = nullptr) const {
    Eigen::VectorXd e(problem.vertices);
    Eigen::VectorXd worst(problem.vertices);
    tbb::parallel_for(0, problem.vertices, [&](int i) {
      const Eigen::Vector3d p = problem.rest.row(i).transpose();
      double sum = 0.0;
      double most = 0.0;
      for (int k = 1; k < problem.examples; ++k) {
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int s = 0; s < kMaxInfluences && weights.bone(i, s) >= 0; ++s) {
          x += weights.weight(i, s) * apply(motions[static_cast<size_t>(k * bones + weights.bone(i, s))], p);
        }
        const double squared = (x - problem.poses[static_cast<size_t>(k)].row(i).transpose()).squaredNorm();
        sum += squared;
        most = std::max(most, squared);
      }
      e(i) = sum;
      worst(i) = std::sqrt(most);
    });
    if (largest != nullptr) *largest = worst;
    return e;
  }

  std::vector<int> primaries() const {
    std::vector<int> primary(static_cast<size_t>(problem.vertices));
    for (int i = 0; i < problem.vertices; ++i) primary[static_cast<size_t>(i)] = weights.primary(i);
    return primary;
  }

  // Removes bones that no vertex uses any more, renumbering the rest in order.
  void drop_unused_bones() {
    std::vector<int> renumber(static_cast<size_t>(bones), -1);
    for (int i = 0; i < problem.vertices; ++i) {
      for (int s = 0; s < kMaxInfluences && weights.bone(i, s) >= 0; ++s) renumber[static_cast<size_t>(weights.bone(i, s))] = 0;
    }
    int kept = 0;
    for (int& r : renumber) r = r == 0 ? kept++ : -1;
    if (kept == bones) return;
    std::vector<RigidMotion> compact(static_cast<size_t>(problem.examples * kept));
    for (int k = 0; k < problem.examples; ++k) {
      for (int j = 0; j < bones; ++j) {
        if (renumber[static_cast<size_t>(j)] >= 0) {
          compact[static_cast<size_t>(k * kept + renumber[static_cast<size_t>(j)])] = motions[static_cast<size_t>(k * bones + j)];
        }
      }
    }
    for (int i = 0; i < problem.vertices; ++i) {
      for (int s = 0; s < kMaxInfluences && weights.bone(i, s) >= 0; ++s) {
        weights.bone(i, s) = renumber[static_cast<size_t>(weights.bone(i, s))];
      }
    }
    motions = std::move(compact);
    bones = kept;
  }
};

}  // namespace

SkinningDecomposition decompose_skinning(const PoseSet& examples, const SkinningOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (examples.pose_count() < 2) {
    throw ArgumentError("skinning decomposition: needs the reference and at least one more example pose, got " +
                        std::to_string(examples.pose_count()));
  }
  check_options(options, examples.vertex_count());
  const Problem problem = make_problem(examples);

  int bones = 0;
  const std::vector<int> labels = rigid_parts(problem, options, bones);
  Alternation alternation{problem, options, bones, {}, {}, nullptr};
  alternation.weights.bone.setConstant(problem.vertices, kMaxInfluences, -1);
  alternation.weights.weight.setZero(problem.vertices, kMaxInfluences);
  for (int i = 0; i < problem.vertices; ++i) {
    alternation.weights.bone(i, 0) = labels[static_cast<size_t>(i)];
    alternation.weights.weight(i, 0) = 1.0;
  }
  alternation.motions = fit_parts(problem, labels, bones);
  alternation.drop_unused_bones();
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    alternation.update_weights();
    alternation.update_motions();
  }
  alternation.drop_unused_bones();
  detail::BoneSkeleton skeleton =
      detail::bone_skeleton(problem.rest, problem.neighbours, alternation.primaries(), problem.mass, alternation.motions,
                            alternation.bones, problem.examples);
  alternation.skeleton = &skeleton;
  for (int iteration = 0; iteration < options.skeleton_iterations; ++iteration) {
    alternation.update_weights();
    alternation.update_motions();
  }
  if (options.skeleton_iterations > 0) {
    // The refinement may leave a bone without vertices; the skeleton is then found again on the rest.
    const int before = alternation.bones;
    alternation.skeleton = nullptr;
    alternation.drop_unused_bones();
    if (alternation.bones != before) {
      skeleton = detail::bone_skeleton(problem.rest, problem.neighbours, alternation.primaries(), problem.mass,
                                       alternation.motions, alternation.bones, problem.examples);
    }
  }

  // Back to the examples' coordinates: x_internal = (x - c) s.
  SkinningDecomposition result;
  bones = alternation.bones;
  result.weights = Eigen::MatrixXd::Zero(problem.vertices, bones);
  for (int i = 0; i < problem.vertices; ++i) {
    for (int s = 0; s < kMaxInfluences && alternation.weights.bone(i, s) >= 0; ++s) {
      result.weights(i, alternation.weights.bone(i, s)) = alternation.weights.weight(i, s);
    }
  }
  const Eigen::Vector3d c = problem.center.transpose();
  result.motions.assign(static_cast<size_t>(problem.examples), std::vector<BoneMotion>(static_cast<size_t>(bones)));
  for (int k = 1; k < problem.examples; ++k) {
    for (int j = 0; j < bones; ++j) {
      const RigidMotion& m = alternation.motions[static_cast<size_t>(k * bones + j)];
      BoneMotion& out = result.motions[static_cast<size_t>(k)][static_cast<size_t>(j)];
      out.rotation = m.leftCols<3>();
      out.translation = m.col(3) / problem.scale + c - out.rotation * c;
    }
  }
  result.parents = skeleton.parents;
  result.joints = (skeleton.joints / problem.scale).rowwise() + problem.center;
  Eigen::VectorXd largest;
  const Eigen::VectorXd errors = alternation.errors(&largest);
  result.rms_error = rms(problem, errors);
  result.max_error = largest.maxCoeff();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Eigen::MatrixX3d skinned_pose(const SkinningDecomposition& decomposition,
                              const Eigen::Ref<const Eigen::MatrixX3d>& reference, int example) {
  if (reference.rows() != decomposition.vertex_count()) {
    throw ArgumentError("skinned_pose: " + std::to_string(reference.rows()) + " reference vertices for weights of " +
                        std::to_string(decomposition.vertex_count()));
  }
  if (example < 0 || example >= decomposition.example_count()) {
    throw ArgumentError("skinned_pose: example " + std::to_string(example) + " outside [0, " +
                        std::to_string(decomposition.example_count()) + ")");
  }
  const std::vector<BoneMotion>& motions = decomposition.motions[static_cast<size_t>(example)];
  Eigen::MatrixX3d result = Eigen::MatrixX3d::Zero(reference.rows(), 3);
  for (int j = 0; j < decomposition.bone_count(); ++j) {
    const BoneMotion& m = motions[static_cast<size_t>(j)];
    const Eigen::MatrixX3d moved = (reference * m.rotation.transpose()).rowwise() + m.translation.transpose();
    result += decomposition.weights.col(j).asDiagonal() * moved;
  }
  return result;
}

void check_skinning_decomposition(const SkinningDecomposition& d) {
  const auto fail = [](const std::string& what) { throw ArgumentError("skinning decomposition: " + what); };
  const int bones = d.bone_count();
  if (bones < 1 || d.vertex_count() < 1) fail("no bone or no vertex");
  if (!d.weights.allFinite()) fail("a weight is not finite");
  if ((d.weights.array() < 0.0).any()) fail("a weight is negative");
  for (int i = 0; i < d.vertex_count(); ++i) {
    if (std::abs(d.weights.row(i).sum() - 1.0) > 1e-6) {
      fail("the weights of vertex " + std::to_string(i) + " sum to " + std::to_string(d.weights.row(i).sum()));
    }
  }
  if (d.example_count() < 2) fail("fewer than two examples");
  for (const std::vector<BoneMotion>& motions : d.motions) {
    if (static_cast<int>(motions.size()) != bones) fail("an example has motions for another number of bones");
    for (const BoneMotion& m : motions) {
      if (!m.rotation.allFinite() || !m.translation.allFinite()) fail("a bone motion is not finite");
    }
  }
  if (static_cast<int>(d.parents.size()) != bones || d.joints.rows() != bones || !d.joints.allFinite()) {
    fail("the skeleton has the wrong size");
  }
  for (int j = 0; j < bones; ++j) {
    // Walking up from any bone must reach a root within `bones` steps.
    int bone = j;
    for (int step = 0; bone >= 0; ++step) {
      if (step > bones || bone >= bones) fail("the parents of the bones do not form a forest");
      bone = d.parents[static_cast<size_t>(bone)];
    }
    if (bone != -1) fail("a parent index is out of range");
  }
}

}  // namespace posekit
