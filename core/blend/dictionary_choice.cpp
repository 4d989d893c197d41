// DictionaryChoice::automatic: the dictionary is chosen by how well it rebuilds examples it has not
// seen. Whether a shape is articulated (the skinning decomposition fits it closely) does not say which
// dictionary serves it better: on the animals measured (docs/deform-register.md) the bones fit within
// about 1 % of the diagonal, yet the Laplace-Beltrami dictionary rebuilt most held-out poses better.
#include <posekit/blended_deformation.hpp>
#include <posekit/geometry.hpp>

#include "blend/deformer_state.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace posekit {
namespace {

double percentile_95_error(const Eigen::MatrixX3d& result, const Eigen::MatrixX3d& truth) {
  const Eigen::VectorXd distance = (result - truth).rowwise().norm();
  std::vector<double> sorted(distance.data(), distance.data() + distance.size());
  const size_t rank = static_cast<size_t>(0.95 * static_cast<double>(sorted.size() - 1) + 0.5);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank), sorted.end());
  return sorted[rank] / bounding_box_diagonal(truth);
}

}  // namespace

bool BlendedDeformer::skeleton_rebuilds_better(const PoseSet& examples, const BlendOptions& options,
                                               BlendSetupReport& report) {
  const int count = examples.pose_count();
  if (count < 3 || options.trial_examples < 1 || options.trial_points < 1) return false;
  // The examples farthest from the reference (mean vertex distance after centring): the poses the
  // other examples span least, where the dictionaries differ most.
  const Eigen::RowVector3d reference_center = examples.pose(0).colwise().mean();
  std::vector<double> distance(static_cast<size_t>(count), 0.0);
  for (int k = 1; k < count; ++k) {
    const Eigen::MatrixX3d centred = examples.pose(k).rowwise() - examples.pose(k).colwise().mean();
    distance[static_cast<size_t>(k)] =
        (centred - (examples.pose(0).rowwise() - reference_center)).rowwise().norm().mean();
  }
  std::vector<int> order(static_cast<size_t>(count - 1));
  std::iota(order.begin(), order.end(), 1);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return distance[static_cast<size_t>(a)] > distance[static_cast<size_t>(b)]; });
  order.resize(static_cast<size_t>(std::min(options.trial_examples, count - 1)));

  BlendOptions trial = options;
  trial.dictionary = DictionaryChoice::skeleton;
  double lbo = 0.0;
  double skeleton = 0.0;
  for (int held_out : order) {
    PoseSet others(examples.faces());
    for (int k = 0; k < count; ++k) {
      if (k != held_out) others.add_pose(examples.pose(k), examples.pose_name(k));
    }
    const Eigen::MatrixX3d& truth = examples.pose(held_out);
    const std::vector<int> points = farthest_point_samples(truth, std::min(options.trial_points, examples.vertex_count()));
    std::vector<LinearConstraint> constraints;
    Eigen::MatrixX3d targets(static_cast<Eigen::Index>(points.size()), 3);
    for (size_t r = 0; r < points.size(); ++r) {
      constraints.push_back(LinearConstraint::vertex(points[r]));
      targets.row(static_cast<Eigen::Index>(r)) = truth.row(points[r]);
    }
    // One deformer of each fold serves both: its own dictionary is the Laplace-Beltrami one.
    BlendedDeformer deformer(others, trial);
    deformer.set_constraints(constraints);
    lbo += percentile_95_error(deformer.deform_in_own_dictionary(targets).vertices, truth);
    skeleton += percentile_95_error(deformer.deform(targets).vertices, truth);
  }
  const double held = static_cast<double>(order.size());
  report.trial.examples = static_cast<int>(order.size());
  report.trial.lbo = lbo / held;
  report.trial.skeleton = skeleton / held;
  return report.trial.skeleton < report.trial.lbo;
}

}  // namespace posekit
