// Interpolation of the shared real poses with the three methods: MixIT's 99th-percentile edge-length
// and dihedral-angle errors stay within 1.5 times the whole-mesh edge-space baseline's and far below
// linear vertex interpolation's, at weights 0.25, 0.5 and 0.75 and for four poses with equal weights.
// The edge-space baseline takes seconds per weight (minutes on the elephant): labelled realdata.
#include <posekit/interpolate.hpp>
#include <posekit/mesh_io.hpp>

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <ostream>
#include <string>

namespace posekit {
namespace {

struct Poses {
  std::string name;
  std::vector<std::string> files;
  std::vector<double> weights_of_second;  // two poses: t for (1 - t, t); empty: equal weights
};

void PrintTo(const Poses& poses, std::ostream* out) { *out << poses.name; }

class InterpolateRealPoses : public ::testing::TestWithParam<Poses> {};

TEST_P(InterpolateRealPoses, MixitIsCloseToTheEdgeMethodAndFarBelowVertices) {
  std::vector<std::filesystem::path> files;
  for (const std::string& file : GetParam().files) {
    const auto path = testing::shared_pose(file);
    if (!path) GTEST_SKIP() << "shared pose data not found: " << file;
    files.push_back(*path);
  }
  const PoseSet poses = read_pose_set(files);
  std::vector<Eigen::VectorXd> weights;
  for (const double t : GetParam().weights_of_second) weights.push_back(two_pose_weights(t));
  if (weights.empty()) weights.push_back(Eigen::VectorXd::Constant(poses.pose_count(), 1.0 / poses.pose_count()));
  std::map<InterpolationMethod, std::unique_ptr<PoseInterpolator>> interpolators;
  for (const InterpolationMethod method : {InterpolationMethod::mixit, InterpolationMethod::edge, InterpolationMethod::vertex}) {
    InterpolationOptions options;
    options.method = method;
    interpolators[method] = std::make_unique<PoseInterpolator>(poses, options);
  }
  for (const Eigen::VectorXd& w : weights) {
    std::map<InterpolationMethod, InterpolationError> errors;
    for (auto& [method, interpolator] : interpolators) {
      const Eigen::MatrixX3d result = interpolator->interpolate(w);
      ASSERT_TRUE(result.allFinite()) << to_string(method);
      errors[method] = interpolator->error(result, w);
    }
    const InterpolationError& mixit = errors[InterpolationMethod::mixit];
    const InterpolationError& edge = errors[InterpolationMethod::edge];
    const InterpolationError& vertex = errors[InterpolationMethod::vertex];
    const std::string at = "weights " + std::to_string(w(0)) + ", ...";
    EXPECT_LE(mixit.edge_length.p99, 1.5 * edge.edge_length.p99) << at;
    EXPECT_LE(mixit.dihedral_degrees.p99, 1.5 * edge.dihedral_degrees.p99) << at;
    EXPECT_LE(mixit.edge_length.p99, 0.3 * vertex.edge_length.p99) << at;
    EXPECT_LE(mixit.flipped_faces, 0.002 * static_cast<double>(poses.faces().rows())) << at;
  }
}

INSTANTIATE_TEST_SUITE_P(
    SharedPoses, InterpolateRealPoses,
    ::testing::Values(Poses{"horse", {"horse-poses/horse-10.obj", "horse-poses/horse-01.obj"}, {0.25, 0.5, 0.75}},
                      Poses{"cat", {"cat-poses/cat-reference.obj", "cat-poses/cat-01.obj"}, {0.25, 0.5, 0.75}},
                      Poses{"lion", {"lion-poses/lion-reference.obj", "lion-poses/lion-03.obj"}, {0.25, 0.5, 0.75}},
                      Poses{"elephant", {"elephant-poses/elephant-01.obj", "elephant-poses/elephant-02.obj"}, {0.5}},
                      Poses{"horse_four",
                            {"horse-poses/horse-10.obj", "horse-poses/horse-01.obj", "horse-poses/horse-03.obj",
                             "horse-poses/horse-05.obj"},
                            {}}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace posekit
