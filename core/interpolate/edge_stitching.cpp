#include "interpolate/edge_stitching.hpp"

#include <posekit/error.hpp>

#include <algorithm>

namespace posekit::interpolation {
namespace {

// A weak pull of every unknown vertex towards the mean of its aligned copies fixes the translation of
// joints that touch no rigid piece.
constexpr double kAnchorWeight = 1e-8;

}  // namespace

EdgeStitching::EdgeStitching(const EdgeMap& edges, const std::vector<MeshComponent>& components,
                             const std::vector<char>& held, int vertex_count)
    : holders_(static_cast<size_t>(edges.edges.rows()), 0),
      unknown_(static_cast<size_t>(vertex_count), -1),
      edges_(edges.edges),
      vertex_count_(vertex_count) {
  for (int v = 0; v < vertex_count; ++v) {
    if (!held[static_cast<size_t>(v)]) unknown_[static_cast<size_t>(v)] = unknown_count_++;
  }
  std::vector<int> row_of(static_cast<size_t>(vertex_count), -1);
  std::vector<Eigen::Triplet<double>> entries;
  for (const MeshComponent& component : components) {
    for (size_t row = 0; row < component.vertices.size(); ++row) row_of[static_cast<size_t>(component.vertices[row])] = static_cast<int>(row);
    std::vector<int> own_edges;
    for (const int f : component.faces) {
      for (int side = 0; side < 3; ++side) own_edges.push_back(edges.face_edges(f, side));
    }
    std::sort(own_edges.begin(), own_edges.end());
    own_edges.erase(std::unique(own_edges.begin(), own_edges.end()), own_edges.end());
    std::vector<ComponentEdge> list;
    for (const int e : own_edges) {
      const int a = unknown_[static_cast<size_t>(edges.edges(e, 0))];
      const int b = unknown_[static_cast<size_t>(edges.edges(e, 1))];
      if (a < 0 && b < 0) continue;  // both ends held: nothing to solve for
      list.push_back({e, row_of[static_cast<size_t>(edges.edges(e, 0))], row_of[static_cast<size_t>(edges.edges(e, 1))]});
      ++holders_[static_cast<size_t>(e)];
      if (a >= 0) entries.emplace_back(a, a, 1.0);
      if (b >= 0) entries.emplace_back(b, b, 1.0);
      if (a >= 0 && b >= 0) {
        entries.emplace_back(a, b, -1.0);
        entries.emplace_back(b, a, -1.0);
      }
    }
    component_edges_.push_back(std::move(list));
    component_vertices_.push_back(component.vertices);
    bool holds_all = !component.vertices.empty();
    for (const int v : component.vertices) holds_all = holds_all && held[static_cast<size_t>(v)];
    holding_.push_back(holds_all);
  }
  anchor_ = kAnchorWeight;
  for (int u = 0; u < unknown_count_; ++u) entries.emplace_back(u, u, anchor_);
  Eigen::SparseMatrix<double> normal(unknown_count_, unknown_count_);
  normal.setFromTriplets(entries.begin(), entries.end());
  solver_.compute(normal);
  if (solver_.info() != Eigen::Success) throw Error("edge stitching: the factorization failed");
}

Eigen::MatrixX3d EdgeStitching::stitch(const std::vector<Eigen::MatrixX3d>& placed,
                                       const Eigen::VectorXd& target_lengths) const {
  // Held vertices where the components that hold them (rigid pieces) put them; the others first at the
  // mean of their aligned copies.
  Eigen::MatrixX3d result = Eigen::MatrixX3d::Zero(vertex_count_, 3);
  Eigen::VectorXd copies = Eigen::VectorXd::Zero(vertex_count_);
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t c = 0; c < placed.size(); ++c) {
      if (holding_[c] != (pass == 0)) continue;
      const std::vector<int>& vertices = component_vertices_[c];
      for (size_t row = 0; row < vertices.size(); ++row) {
        const bool held = unknown_[static_cast<size_t>(vertices[row])] < 0;
        if (pass == 1 && held && copies(vertices[row]) > 0.0) continue;
        result.row(vertices[row]) += placed[c].row(static_cast<Eigen::Index>(row));
        copies(vertices[row]) += 1.0;
      }
    }
  }
  for (int v = 0; v < vertex_count_; ++v) {
    if (copies(v) > 0.0) result.row(v) /= copies(v);
  }
  if (unknown_count_ == 0) return result;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(unknown_count_, 3);
  for (int v = 0; v < vertex_count_; ++v) {
    if (unknown_[static_cast<size_t>(v)] >= 0) rhs.row(unknown_[static_cast<size_t>(v)]) = anchor_ * result.row(v);
  }
  for (size_t c = 0; c < placed.size(); ++c) {
    const Eigen::MatrixX3d& shape = placed[c];
    for (const ComponentEdge& edge : component_edges_[c]) {
      Eigen::RowVector3d vector = shape.row(edge.to) - shape.row(edge.from);
      const double length = vector.norm();
      // Overlapping components disagree slightly; each asks for its direction at the interpolated length.
      if (holders_[static_cast<size_t>(edge.edge)] > 1 && length > 0.0) vector *= target_lengths(edge.edge) / length;
      const int from = edges_(edge.edge, 0);
      const int to = edges_(edge.edge, 1);
      const int a = unknown_[static_cast<size_t>(from)];
      const int b = unknown_[static_cast<size_t>(to)];
      // Row x_to - x_from = vector, with held ends moved to the right-hand side.
      if (b >= 0) rhs.row(b) += a >= 0 ? vector : Eigen::RowVector3d(vector + result.row(from));
      if (a >= 0) rhs.row(a) -= b >= 0 ? vector : Eigen::RowVector3d(vector - result.row(to));
    }
  }
  Eigen::MatrixX3d solved(unknown_count_, 3);
  for (int c = 0; c < 3; ++c) solved.col(c) = solver_.solve(rhs.col(c));
  for (int v = 0; v < vertex_count_; ++v) {
    if (unknown_[static_cast<size_t>(v)] >= 0) result.row(v) = solved.row(unknown_[static_cast<size_t>(v)]);
  }
  return result;
}

}  // namespace posekit::interpolation
