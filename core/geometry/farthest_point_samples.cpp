#include <posekit/error.hpp>
#include <posekit/geometry.hpp>

#include <limits>
#include <string>

namespace posekit {

std::vector<int> farthest_point_samples(const Eigen::Ref<const Eigen::MatrixX3d>& vertices, int count,
                                        std::vector<int> seeds) {
  const Eigen::Index n = vertices.rows();
  for (int v : seeds) {
    if (v < 0 || v >= n) throw ArgumentError("farthest_point_samples: seed " + std::to_string(v) + " is not a vertex");
  }
  if (n == 0) return seeds;
  if (seeds.empty() && count > 0) {
    Eigen::Index first = 0;
    (vertices.rowwise() - vertices.colwise().mean()).rowwise().squaredNorm().maxCoeff(&first);
    seeds.push_back(static_cast<int>(first));
  }
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (int v : seeds) nearest = nearest.cwiseMin((vertices.rowwise() - vertices.row(v)).rowwise().squaredNorm());
  while (static_cast<int>(seeds.size()) < count && static_cast<Eigen::Index>(seeds.size()) < n) {
    Eigen::Index next = 0;
    nearest.maxCoeff(&next);
    seeds.push_back(static_cast<int>(next));
    nearest = nearest.cwiseMin((vertices.rowwise() - vertices.row(next)).rowwise().squaredNorm());
  }
  return seeds;
}

}  // namespace posekit
