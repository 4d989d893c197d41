#include "interpolate/local_global_projection.hpp"

#include <posekit/edge_space.hpp>
#include <posekit/error.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace posekit::interpolation {
namespace {

// A weak pull towards the current positions fixes the translation (and keeps vertices without edges).
constexpr double kAnchorWeight = 1e-6;
// A hinge far off its angle (a fold of the inputs) asks for no more than this turn per pass.
constexpr double kLargestTurn = 0.1;
// Earlier passes that Anderson acceleration mixes.
constexpr int kHistory = 3;

// The side of face f that is the mesh edge between u and v.
int side_between(const Eigen::Ref<const Eigen::MatrixX3i>& faces, const EdgeMap& edges, int f, int u, int v) {
  for (int side = 0; side < 3; ++side) {
    const int p = faces(f, side);
    const int q = faces(f, (side + 1) % 3);
    if ((p == u && q == v) || (p == v && q == u)) return edges.face_edges(f, side);
  }
  return -1;
}

}  // namespace

LocalGlobalProjection::LocalGlobalProjection(const Eigen::Ref<const Eigen::MatrixX3i>& faces, int vertex_count,
                                             const EdgeMap& edges,
                                             const AdjacencyLists& incident_faces, const std::vector<char>& hinge,
                                             const Eigen::VectorXd& reference_lengths, double hinge_weight)
    : edges_(edges.edges), hinge_weight_(hinge_weight), anchor_(kAnchorWeight) {
  if (!(hinge_weight >= 0.0)) throw ArgumentError("local/global projection: the hinge weight must not be negative");
  const int edge_count = static_cast<int>(edges.edges.rows());
  if (reference_lengths.size() != edge_count) throw ArgumentError("local/global projection: one reference length per edge");
  const double typical = reference_lengths.size() > 0 ? reference_lengths.mean() : 1.0;
  // Relative to the typical edge, so that the anchor keeps its meaning; degenerate edges count as typical.
  relative_ = reference_lengths.unaryExpr([typical](double l) { return l > 0.0 ? typical * typical / (l * l) : 1.0; });
  Eigen::VectorXd weights = relative_;
  for (int e = 0; e < edge_count; ++e) {
    if (!hinge[static_cast<size_t>(e)] || incident_faces.count(e) != 2) continue;
    const int first = incident_faces[e][0];
    const int second = incident_faces[e][1];
    MeshHinge h;
    h.edge = e;
    int side = 0;
    while (edges.face_edges(first, side) != e) ++side;
    h.corners.a = faces(first, side);
    h.corners.b = faces(first, (side + 1) % 3);
    h.corners.c = faces(first, (side + 2) % 3);
    for (int corner = 0; corner < 3; ++corner) {
      const int v = faces(second, corner);
      if (v != h.corners.a && v != h.corners.b) h.corners.d = v;
    }
    h.wings = {side_between(faces, edges, first, h.corners.a, h.corners.c),
               side_between(faces, edges, first, h.corners.b, h.corners.c),
               side_between(faces, edges, second, h.corners.a, h.corners.d),
               side_between(faces, edges, second, h.corners.b, h.corners.d)};
    if (h.corners.d < 0 || *std::min_element(h.wings.begin(), h.wings.end()) < 0) continue;
    for (const int wing : h.wings) weights(wing) += hinge_weight * relative_(wing);
    hinges_.push_back(h);
  }
  // Incidence lists, so that each pass gathers its right-hand side in parallel.
  const auto lists = [](int items, const std::vector<std::pair<int, int>>& pairs) {
    std::vector<int> offsets(static_cast<size_t>(items) + 1, 0);
    for (const auto& [item, value] : pairs) ++offsets[static_cast<size_t>(item) + 1];
    for (size_t i = 0; i < static_cast<size_t>(items); ++i) offsets[i + 1] += offsets[i];
    std::vector<int> values(pairs.size());
    std::vector<int> fill(offsets.begin(), offsets.end() - 1);
    for (const auto& [item, value] : pairs) values[static_cast<size_t>(fill[static_cast<size_t>(item)]++)] = value;
    return AdjacencyLists(std::move(offsets), std::move(values));
  };
  std::vector<std::pair<int, int>> roles;
  for (size_t index = 0; index < hinges_.size(); ++index) {
    for (int i = 0; i < 4; ++i) roles.emplace_back(hinges_[index].wings[static_cast<size_t>(i)], static_cast<int>(4 * index) + i);
  }
  wing_roles_ = lists(edge_count, roles);
  std::vector<std::pair<int, int>> incidence;
  for (int e = 0; e < edge_count; ++e) {
    incidence.emplace_back(edges.edges(e, 0), e);
    incidence.emplace_back(edges.edges(e, 1), e);
  }
  vertex_edges_ = lists(vertex_count, incidence);

  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(edge_count) * 4 + static_cast<size_t>(vertex_count));
  for (int e = 0; e < edge_count; ++e) {
    const int a = edges.edges(e, 0);
    const int b = edges.edges(e, 1);
    entries.emplace_back(a, a, weights(e));
    entries.emplace_back(b, b, weights(e));
    entries.emplace_back(a, b, -weights(e));
    entries.emplace_back(b, a, -weights(e));
  }
  for (int v = 0; v < vertex_count; ++v) entries.emplace_back(v, v, anchor_);
  Eigen::SparseMatrix<double> laplacian(vertex_count, vertex_count);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  solver_.compute(laplacian);
  if (solver_.info() != Eigen::Success) throw Error("local/global projection: the factorization failed");
}

void LocalGlobalProjection::project(Eigen::MatrixX3d& x, const Eigen::VectorXd& lengths, const Eigen::VectorXd& angles,
                                    int passes) const {
  const int hinge_count = static_cast<int>(hinges_.size());
  const int edge_count = static_cast<int>(edges_.rows());
  const int vertex_count = static_cast<int>(x.rows());
  std::vector<std::array<Eigen::RowVector3d, 4>> wing_targets(static_cast<size_t>(hinge_count));
  Eigen::MatrixX3d edge_targets(edge_count, 3);
  Eigen::MatrixX3d rhs(vertex_count, 3);
  const auto edge_vector = [&](const Eigen::MatrixX3d& y, int e) {
    return Eigen::RowVector3d(y.row(edges_(e, 1)) - y.row(edges_(e, 0)));
  };
  const auto at_length = [&](Eigen::RowVector3d vector, int e) {
    const double length = vector.norm();
    if (length > 0.0) vector *= lengths(e) / length;
    return vector;
  };
  // One local/global pass: G(y).
  const auto pass_from = [&](const Eigen::MatrixX3d& x_in) {
    const Eigen::MatrixX3d& x = x_in;
    // Local: each hinge's wings turned about the hinge edge, c by -delta / 2 and d by +delta / 2.
    tbb::parallel_for(0, hinge_count, [&](int index) {
      const MeshHinge& h = hinges_[static_cast<size_t>(index)];
      const double delta = std::clamp(wrap_angle(angles(h.edge) - hinge_angle(h.corners, x)), -kLargestTurn, kLargestTurn);
      Eigen::RowVector3d axis = x.row(h.corners.b) - x.row(h.corners.a);
      const double length = axis.norm();
      if (length > 0.0) axis /= length;
      const double cosine = std::cos(0.5 * delta);
      const double sine = std::sin(0.5 * delta);
      for (int i = 0; i < 4; ++i) {
        Eigen::RowVector3d vector = edge_vector(x, h.wings[static_cast<size_t>(i)]);
        if (length > 0.0) {
          // Rodrigues: the wing of c turns by -delta / 2, that of d by +delta / 2.
          const double s = i < 2 ? -sine : sine;
          vector = vector * cosine + axis.cross(vector) * s + axis * (axis.dot(vector) * (1.0 - cosine));
        }
        wing_targets[static_cast<size_t>(index)][static_cast<size_t>(i)] = at_length(vector, h.wings[static_cast<size_t>(i)]);
      }
    });
    // Global: least squares on every edge vector asked for, gathered per edge and then per vertex.
    tbb::parallel_for(0, edge_count, [&](int e) {
      Eigen::RowVector3d target = at_length(edge_vector(x, e), e);
      for (const int role : wing_roles_[e]) {
        target += hinge_weight_ * wing_targets[static_cast<size_t>(role / 4)][static_cast<size_t>(role % 4)];
      }
      edge_targets.row(e) = relative_(e) * target;
    });
    tbb::parallel_for(0, vertex_count, [&](int v) {
      Eigen::RowVector3d sum = anchor_ * x.row(v);
      for (const int e : vertex_edges_[v]) sum += edges_(e, 1) == v ? edge_targets.row(e) : Eigen::RowVector3d(-edge_targets.row(e));
      rhs.row(v) = sum;
    });
    return Eigen::MatrixX3d(solver_.solve(rhs));
  };
  // Anderson acceleration of the fixed-point iteration x = G(x): the next point mixes the last few
  // G values so that the mixed residual G(x) - x is smallest; it restarts whenever a residual grows.
  std::vector<Eigen::VectorXd> g_history;
  std::vector<Eigen::VectorXd> f_history;
  double last_residual = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < passes; ++pass) {
    const Eigen::MatrixX3d g = pass_from(x);
    const Eigen::VectorXd g_flat = Eigen::Map<const Eigen::VectorXd>(g.data(), g.size());
    const Eigen::VectorXd f = g_flat - Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
    const double residual = f.norm();
    if (residual > last_residual) {
      g_history.clear();
      f_history.clear();
    }
    last_residual = residual;
    g_history.push_back(g_flat);
    f_history.push_back(f);
    if (static_cast<int>(g_history.size()) > kHistory + 1) {
      g_history.erase(g_history.begin());
      f_history.erase(f_history.begin());
    }
    const int m = static_cast<int>(f_history.size()) - 1;
    if (m == 0) {
      x = g;
      continue;
    }
    Eigen::MatrixXd df(f.size(), m);
    Eigen::MatrixXd dg(f.size(), m);
    for (int j = 0; j < m; ++j) {
      df.col(j) = f_history[static_cast<size_t>(j) + 1] - f_history[static_cast<size_t>(j)];
      dg.col(j) = g_history[static_cast<size_t>(j) + 1] - g_history[static_cast<size_t>(j)];
    }
    const Eigen::VectorXd gamma = (df.transpose() * df).ldlt().solve(df.transpose() * f);
    const Eigen::VectorXd next = g_flat - dg * gamma;
    if (!next.allFinite()) {
      x = g;
      continue;
    }
    x = Eigen::Map<const Eigen::MatrixX3d>(next.data(), x.rows(), 3);
  }
}

}  // namespace posekit::interpolation
