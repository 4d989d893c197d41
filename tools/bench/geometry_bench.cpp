// Self-intersection detection on the project's demo arm and on real poses (skipped without the data).
// The data folder is $POSEKIT_DATA_DIR, else POSEKIT_BENCH_DATA_DIR given at build time.
#include <posekit/demo_shape.hpp>
#include <posekit/mesh_io.hpp>
#include <posekit/self_intersections.hpp>

#include <posekit/self_intersection_tracker.hpp>
#include <posekit/winding_numbers.hpp>

#include <benchmark/benchmark.h>

#include <tbb/parallel_for.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace {

#ifndef POSEKIT_BENCH_DATA_DIR
#define POSEKIT_BENCH_DATA_DIR ""
#endif

std::optional<std::filesystem::path> shared_pose(const std::string& relative) {
  const char* override_dir = std::getenv("POSEKIT_DATA_DIR");
  const std::filesystem::path folder = override_dir != nullptr ? override_dir : POSEKIT_BENCH_DATA_DIR;
  std::error_code error;
  const std::filesystem::path file = folder / relative;
  if (folder.empty() || !std::filesystem::is_regular_file(file, error)) return std::nullopt;
  return file;
}

// Reading the elephant takes longer than checking it; read each file once per process.
const posekit::Mesh* cached_pose(const std::string& relative) {
  static std::map<std::string, std::optional<posekit::Mesh>> cache;
  auto found = cache.find(relative);
  if (found == cache.end()) {
    const auto file = shared_pose(relative);
    found = cache.emplace(relative, file ? std::optional<posekit::Mesh>(posekit::read_mesh(*file)) : std::nullopt).first;
  }
  return found->second ? &*found->second : nullptr;
}

void run_self_intersections(benchmark::State& state, const posekit::Mesh& mesh) {
  size_t intersecting = 0;
  for (auto _ : state) {
    const std::vector<int> faces = posekit::self_intersecting_faces(mesh.vertices, mesh.faces);
    intersecting = faces.size();
    benchmark::DoNotOptimize(faces.data());
  }
  state.counters["faces"] = static_cast<double>(mesh.faces.rows());
  state.counters["intersecting"] = static_cast<double>(intersecting);
  state.SetItemsProcessed(state.iterations() * mesh.faces.rows());
}

void BM_SelfIntersectionsDemoArm(benchmark::State& state) {
  posekit::DemoArmOptions options;
  options.ring_segments = static_cast<int>(state.range(0));
  options.bend_angles_degrees = {135.0};
  const posekit::PoseSet arm = posekit::make_demo_arm(options);
  run_self_intersections(state, arm.mesh(1));
}
// The detection runs on several threads: wall-clock time is what a caller waits for.
BENCHMARK(BM_SelfIntersectionsDemoArm)->Arg(48)->Arg(96)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_SelfIntersectionsSharedPose(benchmark::State& state, const std::string& relative) {
  const posekit::Mesh* mesh = cached_pose(relative);
  if (mesh == nullptr) {
    state.SkipWithError(("shared pose data not found: " + relative + " (set POSEKIT_DATA_DIR)").c_str());
    return;
  }
  run_self_intersections(state, *mesh);
}
BENCHMARK_CAPTURE(BM_SelfIntersectionsSharedPose, lion_01, std::string("lion-poses/lion-01.obj"))
    ->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SelfIntersectionsSharedPose, elephant_01, std::string("elephant-poses/elephant-01.obj"))
    ->UseRealTime()->Unit(benchmark::kMillisecond);

// The poses a correction tests between its key frames, searched side by side as its classification
// does: 19 straight blends between elephant-01 and elephant-03. (One box search for a few poses in
// turn, on boxes holding each face in all of them, took 1.8 to 4.2 times as long with 2 to 6 poses
// per search: docs/performance.md.)
void BM_SelfIntersectionsOfBlendedPoses(benchmark::State& state) {
  const posekit::Mesh* from = cached_pose("elephant-poses/elephant-01.obj");
  const posekit::Mesh* to = cached_pose("elephant-poses/elephant-03.obj");
  if (from == nullptr || to == nullptr) {
    state.SkipWithError("shared pose data not found: elephant-poses (set POSEKIT_DATA_DIR)");
    return;
  }
  std::vector<Eigen::MatrixX3d> poses;
  for (int i = 1; i < 20; ++i) {
    const double t = i / 20.0;
    poses.push_back((1.0 - t) * from->vertices + t * to->vertices);
  }
  size_t pairs = 0;
  for (auto _ : state) {
    std::vector<std::vector<std::pair<int, int>>> found(poses.size());
    tbb::parallel_for(size_t{0}, poses.size(),
                      [&](size_t i) { found[i] = posekit::self_intersecting_face_pairs(poses[i], from->faces); });
    pairs = 0;
    for (const auto& p : found) pairs += p.size();
    benchmark::DoNotOptimize(found.data());
  }
  state.counters["poses"] = static_cast<double>(poses.size());
  state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_SelfIntersectionsOfBlendedPoses)->UseRealTime()->Unit(benchmark::kMillisecond);

// The intersection oracle of the repair stages: a region of about `range(0)` vertices moved on the
// elephant (84k faces) and tested again, against the whole-mesh test above.
void BM_TrackerProbeSharedPose(benchmark::State& state) {
  const posekit::Mesh* mesh = cached_pose("elephant-poses/elephant-01.obj");
  if (mesh == nullptr) {
    state.SkipWithError("shared pose data not found: elephant-poses/elephant-01.obj (set POSEKIT_DATA_DIR)");
    return;
  }
  const posekit::SelfIntersectionTracker tracker(mesh->vertices, mesh->faces);
  Eigen::MatrixX3d moved = mesh->vertices;
  const Eigen::RowVector3d center = moved.row(0);
  std::vector<std::pair<double, Eigen::Index>> by_distance;
  for (Eigen::Index v = 0; v < moved.rows(); ++v) by_distance.emplace_back((moved.row(v) - center).norm(), v);
  std::nth_element(by_distance.begin(), by_distance.begin() + state.range(0), by_distance.end());
  for (Eigen::Index k = 0; k < state.range(0); ++k) moved.row(by_distance[static_cast<size_t>(k)].second) *= 1.001;
  for (auto _ : state) benchmark::DoNotOptimize(tracker.pairs_if(moved).size());
  state.counters["moved_vertices"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_TrackerProbeSharedPose)->Arg(100)->Arg(1000)->Arg(5000)->UseRealTime()->Unit(benchmark::kMillisecond);

// Winding numbers at `range(0)` vertices of the elephant (the contact separation tests the
// vertices near its contacts).
void BM_WindingNumbersSharedPose(benchmark::State& state) {
  const posekit::Mesh* mesh = cached_pose("elephant-poses/elephant-01.obj");
  if (mesh == nullptr) {
    state.SkipWithError("shared pose data not found: elephant-poses/elephant-01.obj (set POSEKIT_DATA_DIR)");
    return;
  }
  const Eigen::MatrixX3d points = mesh->vertices.topRows(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(posekit::winding_numbers(mesh->vertices, mesh->faces, points).sum());
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_WindingNumbersSharedPose)->Arg(100)->Arg(10000)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
