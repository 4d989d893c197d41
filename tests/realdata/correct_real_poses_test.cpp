// End-to-end correction of real poses with the default options on the CPU device: the result keeps
// the connectivity, has no intersecting face that the reference does not have, and reproduces the
// target up to a median vertex distance of 1e-3 of the bounding-box diagonal.
#include <posekit/correct.hpp>
#include <posekit/cpu_device.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>

namespace posekit {
namespace {

struct PosePair {
  std::string reference;
  std::string target;
};

void PrintTo(const PosePair& pair, std::ostream* out) { *out << pair.reference << " -> " << pair.target; }

class CorrectRealPose : public ::testing::TestWithParam<PosePair> {};

TEST_P(CorrectRealPose, RemovesNewIntersectionsAndReproducesTheRest) {
  POSEKIT_REQUIRE_SHARED_POSE(reference_file, GetParam().reference);
  POSEKIT_REQUIRE_SHARED_POSE(target_file, GetParam().target);
  const Mesh reference = read_mesh(reference_file);
  const Mesh target = read_mesh(target_file);
  ASSERT_EQ(reference.faces, target.faces);

  const std::unique_ptr<Device> device = make_cpu_device();
  CorrectionReport report;
  const Eigen::MatrixX3d result =
      correct_pose(reference.vertices, target.vertices, reference.faces, *device, CorrectionOptions{}, &report);

  ASSERT_EQ(result.rows(), reference.vertices.rows());
  ASSERT_TRUE(result.allFinite());
  const std::vector<int> reference_faces = self_intersecting_faces(reference.vertices, reference.faces);
  const std::vector<int> fresh =
      new_intersecting_faces(self_intersecting_faces(result, reference.faces), reference_faces);
  EXPECT_TRUE(fresh.empty()) << fresh.size() << " new intersecting faces, e.g. face " << fresh.front();
  EXPECT_EQ(report.result.new_intersecting_faces, static_cast<int>(fresh.size()));
  EXPECT_LT(report.result.median_distance_to_target, 1e-3 * report.result.bounding_box_diagonal)
      << "median distance / diagonal = " << report.result.median_distance_to_target / report.result.bounding_box_diagonal;
  for (const FieldRegionReport& region : report.field.regions) EXPECT_EQ(region.integration.failures, 0);
  EXPECT_LT(report.result.intersecting_faces, report.result.target_intersecting_faces);
}

std::string pose_name(const ::testing::TestParamInfo<PosePair>& info) {
  std::string name = info.param.target.substr(info.param.target.rfind('/') + 1);
  name = name.substr(0, name.find('.'));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(SharedPoses, CorrectRealPose,
                         ::testing::Values(PosePair{"lion-poses/lion-reference.obj", "lion-poses/lion-01.obj"},
                                           PosePair{"lion-poses/lion-reference.obj", "lion-poses/lion-03.obj"},
                                           PosePair{"horse-poses/horse-10.obj", "horse-poses/horse-04.obj"},
                                           // Clean only after the rollback and local stages.
                                           PosePair{"cat-poses/cat-reference.obj", "cat-poses/cat-08.obj"},
                                           // Folds only the relaxation undoes.
                                           PosePair{"lion-poses/lion-reference.obj", "lion-poses/lion-08.obj"},
                                           PosePair{"lion-poses/lion-reference.obj", "lion-poses/lion-09.obj"},
                                           // Entangled over much of the pose: the local correction of
                                           // the target itself, then the final reproduction.
                                           PosePair{"lion-poses/lion-reference.obj", "lion-poses/lion-04.obj"},
                                           PosePair{"cat-poses/cat-reference.obj", "cat-poses/cat-04.obj"},
                                           // Clean only in two legs through the halfway pose.
                                           PosePair{"lion-poses/lion-reference.obj", "lion-poses/lion-07.obj"},
                                           // Parts pressed into each other over much of the pose: the
                                           // target's contacts separated.
                                           PosePair{"cat-poses/cat-reference.obj", "cat-poses/cat-07.obj"}),
                         pose_name);

}  // namespace
}  // namespace posekit
