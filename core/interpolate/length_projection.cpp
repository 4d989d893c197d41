#include "interpolate/length_projection.hpp"

#include <posekit/error.hpp>

#include <vector>

namespace posekit::interpolation {
namespace {

// A weak pull towards the current positions fixes the translation (and keeps vertices without edges).
constexpr double kAnchorWeight = 1e-6;

}  // namespace

LengthProjection::LengthProjection(const Eigen::MatrixX2i& edges, int vertex_count)
    : edges_(edges), anchor_(kAnchorWeight) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(edges.rows()) * 4 + static_cast<size_t>(vertex_count));
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    const int a = edges(e, 0);
    const int b = edges(e, 1);
    entries.emplace_back(a, a, 1.0);
    entries.emplace_back(b, b, 1.0);
    entries.emplace_back(a, b, -1.0);
    entries.emplace_back(b, a, -1.0);
  }
  for (int v = 0; v < vertex_count; ++v) entries.emplace_back(v, v, anchor_);
  Eigen::SparseMatrix<double> laplacian(vertex_count, vertex_count);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  solver_.compute(laplacian);
  if (solver_.info() != Eigen::Success) throw Error("length projection: the factorization failed");
}

void LengthProjection::project(Eigen::MatrixX3d& x, const Eigen::VectorXd& lengths, int passes) const {
  for (int pass = 0; pass < passes; ++pass) {
    Eigen::MatrixX3d rhs = anchor_ * x;
    for (Eigen::Index e = 0; e < edges_.rows(); ++e) {
      Eigen::RowVector3d vector = x.row(edges_(e, 1)) - x.row(edges_(e, 0));
      const double length = vector.norm();
      if (length > 0.0) vector *= lengths(e) / length;
      rhs.row(edges_(e, 1)) += vector;
      rhs.row(edges_(e, 0)) -= vector;
    }
    for (int c = 0; c < 3; ++c) x.col(c) = solver_.solve(rhs.col(c));
  }
}

}  // namespace posekit::interpolation
