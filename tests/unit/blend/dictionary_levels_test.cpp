// The change to a richer dictionary inside a deformation: a coarse deformer (few eigenfunctions)
// starts, its maps are carried to a finer one by least squares, which continues from there.
#include <gtest/gtest.h>

#include <posekit/blended_deformation.hpp>
#include <posekit/laplace_beltrami.hpp>

#include "blend_test_shapes.hpp"

namespace posekit {
namespace {

TEST(DictionaryLevels, ACoarseStartCarriedToARicherDictionary) {
  const PoseSet examples = testing::small_arm({0.0, 45.0, 90.0, 135.0});
  const PoseSet target = testing::small_arm({112.5});
  BlendOptions coarse_options;
  coarse_options.eigenfunctions = 6;
  BlendedDeformer coarse(examples, coarse_options);
  BlendedDeformer fine(examples);
  const std::vector<int> points = testing::spread_vertices(target.pose(0), 10);
  std::vector<LinearConstraint> constraints;
  Eigen::MatrixX3d positions(10, 3);
  for (int r = 0; r < 10; ++r) {
    constraints.push_back(LinearConstraint::vertex(points[static_cast<size_t>(r)]));
    positions.row(r) = target.pose(0).row(points[static_cast<size_t>(r)]);
  }
  coarse.set_constraints(constraints);
  fine.set_constraints(constraints);
  const BlendResult start = coarse.deform(positions);

  // Both deformers share the internal frame (that of the reference), so the maps carry over.
  const Eigen::VectorXd mass = lumped_mass(fine.dictionary().examples().front(), examples.faces());
  const DictionaryChange change(coarse.dictionary(), fine.dictionary(), mass);
  BlendResult carried = start;
  carried.transformations = change(start.transformations);
  // The reduced fine dictionary spans the coarse one up to round-off.
  EXPECT_LT(testing::max_distortion(fine.vertices(carried.transformations), start.vertices, examples.faces()), 1e-4);

  const BlendResult refined = fine.deform(positions, carried, 0, 4);
  EXPECT_EQ(refined.iterations.front().stage, "minimal");
  EXPECT_LT(testing::max_distortion(refined.vertices, target.pose(0), examples.faces()), 0.025);
}

}  // namespace
}  // namespace posekit
