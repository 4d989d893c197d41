// One real pose reconstructed from the others of its set (skipped when ../shared/data is absent):
// the quick check of the default CI; tests/realdata and posekit_blend_evaluation do all of them.
#include <gtest/gtest.h>

#include <posekit/blended_deformation.hpp>
#include <posekit/mesh_io.hpp>

#include "blend_test_shapes.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

TEST(BlendRealPoses, LionReconstructedFromTheOtherNine) {
  POSEKIT_REQUIRE_SHARED_POSE(target_file, "lion-poses/lion-01.obj");
  std::vector<std::filesystem::path> files{target_file.parent_path() / "lion-reference.obj"};
  for (int k = 2; k <= 9; ++k) files.push_back(target_file.parent_path() / ("lion-0" + std::to_string(k) + ".obj"));
  const PoseSet examples = read_pose_set(files);
  const Mesh target = read_mesh(target_file);
  BlendedDeformer deformer(examples);
  EXPECT_EQ(deformer.setup_report().atoms, 360);

  std::vector<LinearConstraint> all;
  for (int v = 0; v < examples.vertex_count(); ++v) all.push_back(LinearConstraint::vertex(v));
  deformer.set_constraints(all);
  // Measured 1.33 %: the dictionary spans the unseen pose closely.
  EXPECT_LT(testing::max_distortion(deformer.deform(target.vertices).vertices, target.vertices, target.faces), 0.025);

  const std::vector<int> points = testing::spread_vertices(examples.pose(0), 20);
  std::vector<LinearConstraint> few;
  Eigen::MatrixX3d positions(20, 3);
  for (int r = 0; r < 20; ++r) {
    few.push_back(LinearConstraint::vertex(points[static_cast<size_t>(r)]));
    positions.row(r) = target.vertices.row(points[static_cast<size_t>(r)]);
  }
  deformer.set_constraints(few);
  const BlendResult result = deformer.deform(positions);
  const Eigen::VectorXd error =
      (result.vertices - target.vertices).rowwise().norm() / std::sqrt(face_areas(target.vertices, target.faces).sum());
  // Measured 7.0 % and 1.83 %; the nearest example, rigidly placed, is off by 11 % on average.
  EXPECT_LT(error.maxCoeff(), 0.09);
  EXPECT_LT(error.mean(), 0.025);
}

}  // namespace
}  // namespace posekit
