// Example-based deformation on every shared pose set (skipped when ../shared/data is absent): the
// first pose of each set reconstructed from the others, from all its vertices and from 10, and
// registered from a partial scan (40 % of the surface removed around three seeds far from 8 feature
// points). The bounds sit above what posekit_blend_evaluation measures for these poses.
#include <posekit/blended_deformation.hpp>
#include <posekit/geometry.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/partial_registration.hpp>
#include <posekit/skinning_decomposition.hpp>
#include <posekit/topology.hpp>

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <queue>

namespace posekit {
namespace {

struct SetCase {
  std::string folder;
  double all_vertices_max;    // largest distortion with every vertex constrained
  double ten_points_mean;     // mean distortion from 10 vertices
  double correct_fraction;    // registration: correspondences within 5 % of sqrt(area)
};

void PrintTo(const SetCase& c, std::ostream* out) { *out << c.folder; }

std::vector<int> spread(const Eigen::MatrixX3d& v, int count, std::vector<int> chosen = {}) {
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(v.rows(), std::numeric_limits<double>::infinity());
  if (chosen.empty()) {
    Eigen::Index first = 0;
    (v.rowwise() - v.colwise().mean()).rowwise().squaredNorm().maxCoeff(&first);
    chosen.push_back(static_cast<int>(first));
  }
  for (int c : chosen) nearest = nearest.cwiseMin((v.rowwise() - v.row(c)).rowwise().squaredNorm());
  while (static_cast<int>(chosen.size()) < count) {
    Eigen::Index next = 0;
    nearest.maxCoeff(&next);
    chosen.push_back(static_cast<int>(next));
    nearest = nearest.cwiseMin((v.rowwise() - v.row(next)).rowwise().squaredNorm());
  }
  return chosen;
}

class BlendRealSet : public ::testing::TestWithParam<SetCase> {};

TEST_P(BlendRealSet, ReconstructsAndRegistersTheFirstPose) {
  const SetCase& c = GetParam();
  const auto data = testing::shared_data();
  if (!data || !std::filesystem::exists(*data / c.folder)) GTEST_SKIP() << "shared pose data not found: " << c.folder;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(*data / c.folder)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::stable_partition(files.begin(), files.end(), [](const std::filesystem::path& p) {
    return p.filename().string().find("reference") != std::string::npos;
  });
  const Mesh target = read_mesh(files.front());
  const PoseSet examples = read_pose_set(std::vector<std::filesystem::path>(files.begin() + 1, files.end()));
  BlendedDeformer deformer(examples);
  const double length = std::sqrt(face_areas(target.vertices, target.faces).sum());

  std::vector<LinearConstraint> all;
  for (int v = 0; v < examples.vertex_count(); ++v) all.push_back(LinearConstraint::vertex(v));
  deformer.set_constraints(all);
  const BlendResult full = deformer.deform(target.vertices);
  EXPECT_LT((full.vertices - target.vertices).rowwise().norm().maxCoeff() / length, c.all_vertices_max);

  const std::vector<int> ten = spread(target.vertices, 10);
  std::vector<LinearConstraint> few;
  Eigen::MatrixX3d positions(10, 3);
  for (int r = 0; r < 10; ++r) {
    few.push_back(LinearConstraint::vertex(ten[static_cast<size_t>(r)]));
    positions.row(r) = target.vertices.row(ten[static_cast<size_t>(r)]);
  }
  deformer.set_constraints(few);
  const BlendResult sparse = deformer.deform(positions);
  EXPECT_LT((sparse.vertices - target.vertices).rowwise().norm().mean() / length, c.ten_points_mean);

  // The scan: remove faces outwards from three seeds far from the 8 features until 40 % of the area
  // is gone, keeping geodesic discs (along edges) of radius 0.15 sqrt(area) around the features.
  const std::vector<int> features = spread(target.vertices, 8);
  const std::vector<int> seeds = spread(target.vertices, 11, features);
  const Eigen::MatrixX3i& faces = target.faces;
  const AdjacencyLists ring = vertex_neighbours(faces, examples.vertex_count());
  std::vector<char> keep_vertex(static_cast<size_t>(examples.vertex_count()), 0);
  for (int f : features) {
    std::vector<double> d(keep_vertex.size(), std::numeric_limits<double>::infinity());
    std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, std::greater<>> queue;
    d[static_cast<size_t>(f)] = 0.0;
    queue.push({0.0, f});
    while (!queue.empty()) {
      const auto [dist, v] = queue.top();
      queue.pop();
      if (dist > d[static_cast<size_t>(v)] || dist > 0.15 * length) continue;
      keep_vertex[static_cast<size_t>(v)] = 1;
      for (int u : ring[v]) {
        const double next = dist + (target.vertices.row(u) - target.vertices.row(v)).norm();
        if (next < d[static_cast<size_t>(u)]) {
          d[static_cast<size_t>(u)] = next;
          queue.push({next, u});
        }
      }
    }
  }
  const Eigen::VectorXd areas = face_areas(target.vertices, faces);
  std::vector<std::pair<double, int>> order;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVector3d centroid =
        (target.vertices.row(faces(f, 0)) + target.vertices.row(faces(f, 1)) + target.vertices.row(faces(f, 2))) / 3;
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t s = 8; s < seeds.size(); ++s) nearest = std::min(nearest, (centroid - target.vertices.row(seeds[s])).norm());
    order.push_back({nearest, static_cast<int>(f)});
  }
  std::sort(order.begin(), order.end());
  std::vector<char> removed(static_cast<size_t>(faces.rows()), 0);
  double gone = 0.0;
  for (const auto& [distance, f] : order) {
    if (gone >= 0.4 * areas.sum()) break;
    if (keep_vertex[static_cast<size_t>(faces(f, 0))] || keep_vertex[static_cast<size_t>(faces(f, 1))] ||
        keep_vertex[static_cast<size_t>(faces(f, 2))]) {
      continue;
    }
    removed[static_cast<size_t>(f)] = 1;
    gone += areas(f);
  }
  std::vector<int> original;
  std::vector<int> index(keep_vertex.size(), -1);
  Mesh scan;
  std::vector<Eigen::RowVector3i> kept;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (removed[static_cast<size_t>(f)]) continue;
    Eigen::RowVector3i face;
    for (int k = 0; k < 3; ++k) {
      int& i = index[static_cast<size_t>(faces(f, k))];
      if (i < 0) {
        i = static_cast<int>(original.size());
        original.push_back(faces(f, k));
      }
      face(k) = i;
    }
    kept.push_back(face);
  }
  scan.vertices.resize(static_cast<Eigen::Index>(original.size()), 3);
  for (size_t i = 0; i < original.size(); ++i) scan.vertices.row(static_cast<Eigen::Index>(i)) = target.vertices.row(original[i]);
  scan.faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t f = 0; f < kept.size(); ++f) scan.faces.row(static_cast<Eigen::Index>(f)) = kept[f];
  Eigen::MatrixX3d feature_positions(8, 3);
  for (int r = 0; r < 8; ++r) feature_positions.row(r) = target.vertices.row(features[static_cast<size_t>(r)]);
  const ScanRegistration reg = register_partial_scan(deformer, scan, features, feature_positions);
  size_t good = 0;
  for (Eigen::Index i = 0; i < scan.vertices.rows(); ++i) {
    good += (target.vertices.row(reg.correspondence(i)) - target.vertices.row(original[static_cast<size_t>(i)])).norm() <
            0.05 * length;
  }
  EXPECT_GT(static_cast<double>(good) / static_cast<double>(original.size()), c.correct_fraction)
      << "removed " << gone / areas.sum();
}

// The skinning decomposition of the ten horse poses, and the skeleton dictionary made from it: the
// bounds sit above what posekit_blend_evaluation and posekit_blend_bench measure.
TEST(SkeletonRealPoses, HorseBonesFitTheExamplesAndTheirDictionaryRebuildsAPose) {
  const auto data = testing::shared_data();
  if (!data || !std::filesystem::exists(*data / "horse-poses")) GTEST_SKIP() << "shared pose data not found: horse-poses";
  std::vector<std::filesystem::path> files;
  for (int k = 1; k <= 10; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "horse-%02d.obj", k);
    files.push_back(*data / "horse-poses" / name);
  }
  const PoseSet all = read_pose_set(files);
  const SkinningDecomposition skinning = decompose_skinning(all);
  EXPECT_NO_THROW(check_skinning_decomposition(skinning));
  EXPECT_LE(skinning.bone_count(), SkinningOptions{}.max_bones);
  EXPECT_LT(skinning.rms_error, 0.01);
  EXPECT_EQ(std::count(skinning.parents.begin(), skinning.parents.end(), -1), 1);

  // horse-01 from the other nine and 20 of its vertices, with the skeleton dictionary.
  PoseSet examples(all.faces());
  for (int k = 1; k < 10; ++k) examples.add_pose(all.pose(k));
  BlendOptions options;
  options.dictionary = DictionaryChoice::skeleton;
  BlendedDeformer deformer(examples, options);
  ASSERT_EQ(deformer.setup_report().dictionary, "skeleton");
  const Eigen::MatrixX3d& truth = all.pose(0);
  const std::vector<int> twenty = farthest_point_samples(truth, 20);
  std::vector<LinearConstraint> constraints;
  Eigen::MatrixX3d positions(20, 3);
  for (int r = 0; r < 20; ++r) {
    constraints.push_back(LinearConstraint::vertex(twenty[static_cast<size_t>(r)]));
    positions.row(r) = truth.row(twenty[static_cast<size_t>(r)]);
  }
  deformer.set_constraints(constraints);
  const Eigen::VectorXd error = (deformer.deform(positions).vertices - truth).rowwise().norm();
  std::vector<double> sorted(error.data(), error.data() + error.size());
  std::sort(sorted.begin(), sorted.end());
  EXPECT_LT(sorted[static_cast<size_t>(0.95 * static_cast<double>(sorted.size() - 1) + 0.5)] / bounding_box_diagonal(truth),
            0.05);
}

INSTANTIATE_TEST_SUITE_P(Sets, BlendRealSet,
                         ::testing::Values(SetCase{"horse-poses", 0.02, 0.04, 0.9}, SetCase{"cat-poses", 0.02, 0.06, 0.8},
                                           SetCase{"lion-poses", 0.02, 0.04, 0.85},
                                           SetCase{"elephant-poses", 0.03, 0.05, 0.8}),
                         [](const ::testing::TestParamInfo<SetCase>& info) {
                           std::string name = info.param.folder;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace posekit
