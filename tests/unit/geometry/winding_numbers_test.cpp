// Winding numbers: far clusters count as dipoles, so every value is held against the exact sum of
// solid angles, inside, outside, on the surface and near it.
#include <posekit/demo_shape.hpp>
#include <posekit/winding_numbers.hpp>

#include "icosphere.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <optional>
#include <random>

namespace posekit {
namespace {

double exact_winding_number(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, const Eigen::Vector3d& p) {
  double sum = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d u = vertices.row(faces(f, 0)).transpose() - p;
    const Eigen::Vector3d v = vertices.row(faces(f, 1)).transpose() - p;
    const Eigen::Vector3d w = vertices.row(faces(f, 2)).transpose() - p;
    const double lu = u.norm(), lv = v.norm(), lw = w.norm();
    if (lu == 0.0 || lv == 0.0 || lw == 0.0) continue;
    sum += 2.0 * std::atan2(u.dot(v.cross(w)), lu * lv * lw + u.dot(v) * lw + v.dot(w) * lu + w.dot(u) * lv);
  }
  return sum / (4.0 * M_PI);
}

TEST(WindingNumbers, OneInsideHalfOnTheSurfaceZeroOutside) {
  const Mesh sphere = testing::icosphere(3);
  Eigen::MatrixX3d points(4, 3);
  points << 0, 0, 0, 0.5, 0.2, -0.1, 3, 0, 0, 0, 0, 0;
  points.row(3) = sphere.vertices.row(100);
  const Eigen::VectorXd winding = winding_numbers(sphere.vertices, sphere.faces, points);
  EXPECT_NEAR(winding(0), 1.0, 1e-2);
  EXPECT_NEAR(winding(1), 1.0, 1e-2);
  EXPECT_NEAR(winding(2), 0.0, 1e-2);
  EXPECT_NEAR(winding(3), 0.5, 0.05);
}

// The bent demo arm folds its inner elbow through itself: points there lie inside two layers.
TEST(WindingNumbers, AgreeWithTheExactSumOnASelfIntersectingShape) {
  DemoArmOptions options;
  options.bend_angles_degrees = {150.0};
  const PoseSet arm = make_demo_arm(options);
  const Eigen::MatrixX3d& vertices = arm.pose(1);
  std::mt19937 random(3);
  const Eigen::RowVector3d low = vertices.colwise().minCoeff().array() - 0.3;
  const Eigen::RowVector3d high = vertices.colwise().maxCoeff().array() + 0.3;
  Eigen::MatrixX3d points(300, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (i % 3 == 0) {  // on the surface
      points.row(i) = vertices.row(std::uniform_int_distribution<Eigen::Index>(0, vertices.rows() - 1)(random));
    } else {
      for (int axis = 0; axis < 3; ++axis) {
        points(i, axis) = std::uniform_real_distribution<double>(low(axis), high(axis))(random);
      }
    }
  }
  const Eigen::VectorXd winding = winding_numbers(vertices, arm.faces(), points);
  int beyond_one = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double exact = exact_winding_number(vertices, arm.faces(), points.row(i).transpose());
    EXPECT_NEAR(winding(i), exact, 2e-2) << "point " << i;
    beyond_one += exact > 1.5 ? 1 : 0;
  }
  EXPECT_GT(beyond_one, 0);  // some points lie inside both layers of the fold
}

// The tree's halves are built in parallel on large meshes; the tree, and so every value, must be the
// one a single thread builds. A tree kept for later answers as the one-off function does.
TEST(WindingNumbers, TheSameBitsOnAnyNumberOfThreadsAndFromAKeptTree) {
  const Mesh sphere = testing::icosphere(5);  // 20,480 faces: several levels split in parallel
  Eigen::MatrixX3d vertices = sphere.vertices;
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) vertices(v, 0) *= 1.0 + 0.3 * std::sin(3.0 * vertices(v, 1));
  Eigen::MatrixX3d points = 1.01 * vertices.topRows(500);
  points.bottomRows(250) *= 0.9;
  const Eigen::VectorXd parallel = winding_numbers(vertices, sphere.faces, points);
  Eigen::VectorXd serial;
  tbb::task_arena one_thread(1);
  one_thread.execute([&] { serial = winding_numbers(vertices, sphere.faces, points); });
  ASSERT_EQ(parallel.size(), serial.size());
  for (Eigen::Index i = 0; i < parallel.size(); ++i) EXPECT_EQ(parallel(i), serial(i)) << "point " << i;

  std::optional<WindingNumberTree> kept;
  {
    const Eigen::MatrixX3d copy = vertices;  // the tree keeps its own copy
    kept.emplace(copy, sphere.faces);
  }
  const WindingNumberTree moved = std::move(*kept);
  const Eigen::VectorXd from_tree = moved.at(points);
  for (Eigen::Index i = 0; i < parallel.size(); ++i) EXPECT_EQ(from_tree(i), parallel(i)) << "point " << i;
  // The tree of the parallel build holds the dipole bound (the exact-sum tests above use meshes too
  // small to split in parallel).
  for (Eigen::Index i = 0; i < points.rows(); i += 25) {
    EXPECT_NEAR(from_tree(i), exact_winding_number(vertices, sphere.faces, points.row(i).transpose()), 2e-2)
        << "point " << i;
  }
}

}  // namespace
}  // namespace posekit
